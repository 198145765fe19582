#include "emulator/ubx_device.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>

#include "core/sat_table.hpp"
#include "emulator/ubx_aiding.hpp"
#include "models/reuse.hpp"

namespace navemu {

namespace {

using namespace ubx;

constexpr std::uint16_t key(MsgId id) { return static_cast<std::uint16_t>(id.cls << 8 | id.id); }

// The ports as the configuration items name them (CFG-MSGOUT-..._<PORT>, CFG-<PORT>INPROT-...).
constexpr const char* kPortNames[kReceiverPorts] = {"I2C", "UART1", "UART2", "USB", "SPI"};

// NMEA sentences in CFG-MSG (class 0xF0) by their message ID (UBX-13003221 "NMEA messages
// overview"), as far as the device sends them.
constexpr std::pair<std::uint8_t, const char*> kNmeaIds[] = {
    {0x00, "GGA"}, {0x01, "GLL"}, {0x02, "GSA"}, {0x03, "GSV"},
    {0x04, "RMC"}, {0x05, "VTG"}, {0x07, "GST"}, {0x08, "ZDA"}};

// A configuration item's ID by name; 0 when this database does not have it.
std::uint32_t item(const std::string& name) {
  const CfgKey* k = find_config_key(name);
  return k ? k->id : 0;
}

std::string msgout_name(MsgId id) {
  if (id.cls == kClassNmea)
    for (const auto& [nid, n] : kNmeaIds)
      if (nid == id.id) return std::string("NMEA_ID_") + n;
  if (const UbxOutput* o = find_ubx_output(id)) return std::string(o->msgout);
  if (const MessageInfo* m = find_message(id)) {  // "NAV-TIMELS" -> "UBX_NAV_TIMELS"
    std::string n = "UBX_" + std::string(m->name);
    std::replace(n.begin(), n.end(), '-', '_');
    return n;
  }
  return {};
}

// A protocol flag of a port: CFG-UART1INPROT-UBX and the like.
std::uint32_t proto_item(std::uint8_t port, bool in, const char* proto) {
  return item(std::string("CFG-") + kPortNames[port] + (in ? "INPROT-" : "OUTPROT-") + proto);
}

std::uint32_t baud_item(std::uint8_t port) {
  return port == kPortUart1 || port == kPortUart2 ? item(std::string("CFG-") + kPortNames[port] + "-BAUDRATE")
                                                  : 0;
}

// The profile's power-up configuration as default-layer values: its baud and measurement
// rate, and on every port but UART2 its NMEA sentences, UBX messages and NMEA output on or off
// (the parts send the same at power-up on I2C, UART1, USB and SPI; UART2 is an RTCM port:
// F9 HPG 1.13 description, CFG-UART2OUTPROT defaults).
std::vector<std::pair<std::uint32_t, std::uint64_t>> profile_defaults(const GnssProfile& p) {
  std::vector<std::pair<std::uint32_t, std::uint64_t>> d;
  const auto add = [&](std::uint32_t id, std::uint64_t v) {
    if (id) d.emplace_back(id, v);
  };
  add(item("CFG-UART1-BAUDRATE"), static_cast<std::uint64_t>(p.baud));
  add(item("CFG-RATE-MEAS"), static_cast<std::uint64_t>(std::lround(1000.0 / p.rate_hz)));
  add(item("CFG-NAVSPG-INFIL_MINELEV"), static_cast<std::uint64_t>(std::lround(p.elevation_mask_deg)));
  for (std::uint8_t port : kPortsButUart2) {
    const std::string suffix = std::string("_") + kPortNames[port];
    add(proto_item(port, false, "NMEA"), p.ubx->nmea_out ? 1 : 0);
    for (const auto& id_name : kNmeaIds) {
      const char* n = id_name.second;  // a plain name: clang's lambdas take no structured binding
      const auto it =
          std::find_if(p.sentences.begin(), p.sentences.end(), [&](const auto& s) { return s.first == n; });
      add(item(std::string("CFG-MSGOUT-NMEA_ID_") + n + suffix),
          it == p.sentences.end() ? 0 : static_cast<std::uint64_t>(it->second));
    }
    for (const auto& [name, rate] : p.ubx->messages)
      if (const MessageInfo* m = find_message(name))
        add(item("CFG-MSGOUT-" + msgout_name(m->id) + suffix), static_cast<std::uint64_t>(rate));
  }
  // A u-blox 8 standard-precision part takes no RTCM 3 and sends none (UBX-13003221 R25, 1.5
  // "Supported protocols": RTCM 3 only on the high-precision and timing products).
  if (p.ubx->protver < "20")
    for (std::uint8_t port = 0; port < kReceiverPorts; ++port)
      for (bool in : {true, false}) add(proto_item(port, in, "RTCM3X"), 0);
  return d;
}

// The dynamic platform models' sanity limits (ZED-F9P integration manual UBX-18010802, 3.1.7.1,
// "Dynamic platform model details", the same in the u-blox 8 description): maximum altitude,
// horizontal and vertical speed; the airborne models check the altitude only and give no 2D
// fix ("Dynamic platform models"). The bike model (10) has no row there: unchecked.
struct PlatformLimits {
  std::uint8_t dyn_model;
  double max_alt_m, max_h_mps, max_v_mps;
  bool airborne;
};
constexpr PlatformLimits kPlatformLimits[] = {
    {CfgNav5::kDynPortable, 12000, 310, 50, false},  {CfgNav5::kDynStationary, 9000, 10, 6, false},
    {CfgNav5::kDynPedestrian, 9000, 30, 20, false},  {CfgNav5::kDynAutomotive, 6000, 100, 15, false},
    {CfgNav5::kDynSea, 500, 25, 5, false},           {CfgNav5::kDynAirborne1g, 50000, 100, 100, true},
    {CfgNav5::kDynAirborne2g, 50000, 250, 100, true}, {CfgNav5::kDynAirborne4g, 50000, 500, 100, true},
    {CfgNav5::kDynWrist, 9000, 30, 20, false}};

namespace {
// The F9's systems in CFG-GNSS (F9 interface description UBX-18010854, "UBX-CFG-GNSS", flags
// sigCfgMask): gnssId, channels as the u-blox 8's, the CFG-SIGNAL enable of the system, and
// each sigCfgMask bit with the signal's enable.
struct F9GnssBlock {
  std::uint8_t gnss_id, res_trk_ch, max_trk_ch;
  const char* enable;
  std::array<std::pair<std::uint8_t, const char*>, 3> signals;
};
constexpr F9GnssBlock kF9GnssBlocks[] = {
    {0, 8, 16, "CFG-SIGNAL-GPS_ENA", {{{0x01, "CFG-SIGNAL-GPS_L1CA_ENA"}, {0x10, "CFG-SIGNAL-GPS_L2C_ENA"}, {0, nullptr}}}},
    {1, 1, 3, "CFG-SIGNAL-SBAS_ENA", {{{0x01, "CFG-SIGNAL-SBAS_L1CA_ENA"}, {0, nullptr}, {0, nullptr}}}},
    {2, 4, 8, "CFG-SIGNAL-GAL_ENA", {{{0x01, "CFG-SIGNAL-GAL_E1_ENA"}, {0x20, "CFG-SIGNAL-GAL_E5B_ENA"}, {0, nullptr}}}},
    {3, 8, 16, "CFG-SIGNAL-BDS_ENA", {{{0x01, "CFG-SIGNAL-BDS_B1_ENA"}, {0x10, "CFG-SIGNAL-BDS_B2_ENA"}, {0, nullptr}}}},
    {5, 0, 3, "CFG-SIGNAL-QZSS_ENA",
     {{{0x01, "CFG-SIGNAL-QZSS_L1CA_ENA"}, {0x04, "CFG-SIGNAL-QZSS_L1S_ENA"}, {0x10, "CFG-SIGNAL-QZSS_L2C_ENA"}}}},
    {6, 8, 14, "CFG-SIGNAL-GLO_ENA", {{{0x01, "CFG-SIGNAL-GLO_L1_ENA"}, {0x10, "CFG-SIGNAL-GLO_L2_ENA"}, {0, nullptr}}}},
};
// The major GNSS (GPS, Galileo, BeiDou, GLONASS), of which the u-blox 8 runs 3 at once
// (MON-GNSS simultaneous).
bool major_gnss(std::uint8_t gnss_id) { return gnss_id == 0 || gnss_id == 2 || gnss_id == 3 || gnss_id == 6; }

// The systems tracked under a CFG-GNSS configuration: a system is tracked while enabled
// with the sigCfgMask bits `signals` (0x01: its L1 signal; 0x30: its second-band signal, GPS,
// QZSS and GLONASS L2, BeiDou B2I 0x10, Galileo E5b 0x20).
std::uint32_t systems_of(const CfgGnss& g, std::uint32_t signals = 0x01) {
  std::uint32_t s = 0;
  for (const CfgGnssBlock& b : g.blocks) {
    const std::optional<SatId> sat = SatId::from_ubx(b.gnss_id, b.gnss_id == 1 ? 120 : 1);
    if (sat && (b.flags & CfgGnssBlock::kEnable) && (b.flags >> CfgGnssBlock::kSigCfgMaskShift & signals))
      s |= system_bit(sat->system());
  }
  return s;
}
}  // namespace

// The position engine's settings from its CFG-NAVSPG items (integration manual 3.1.7 "Navigation
// configuration": platform, input filters; the u-blox 8's CFG-NAV5 sets the same items).
NavEngineSettings engine_settings_of(const UbxConfig& c) {
  const auto raw = [&](const char* name) { return c.get(item(name)); };
  NavEngineSettings s;
  s.elevation_mask_deg = static_cast<std::int8_t>(raw("CFG-NAVSPG-INFIL_MINELEV"));
  s.min_cn0_dbhz = static_cast<double>(raw("CFG-NAVSPG-INFIL_MINCNO"));
  s.cn0_threshold_sats = static_cast<int>(raw("CFG-NAVSPG-INFIL_NCNOTHRS"));
  s.cn0_threshold_dbhz = static_cast<double>(raw("CFG-NAVSPG-INFIL_CNOTHRS"));
  s.fixed_height_msl_m =
      0.01 * static_cast<std::int32_t>(static_cast<std::uint32_t>(raw("CFG-NAVSPG-CONSTR_ALT")));
  switch (raw("CFG-NAVSPG-FIXMODE")) {
    case 1: s.fix_mode = SolverFixMode::k2DOnly; break;
    case 2: s.fix_mode = SolverFixMode::k3DOnly; break;
    default: s.fix_mode = SolverFixMode::kAuto; break;
  }
  const auto dyn = static_cast<std::uint8_t>(raw("CFG-NAVSPG-DYNMODEL"));
  for (const PlatformLimits& p : kPlatformLimits) {
    if (p.dyn_model != dyn) continue;
    s.max_height_msl_m = p.max_alt_m;
    if (!p.airborne) {
      s.max_h_speed_mps = p.max_h_mps;
      s.max_v_speed_mps = p.max_v_mps;
    } else if (s.fix_mode == SolverFixMode::kAuto) {
      s.fix_mode = SolverFixMode::k3DOnly;
    }
  }
  s.zero_velocity = dyn == CfgNav5::kDynStationary;  // "velocity restricted to 0 m/s"
  return s;
}

// Which configuration items the part has: those of its firmware, as MON-VER's FWVER extension
// names it (F9 HPG 1.13 UBX-21023318 for HPG 1.1x, F9 HPG 1.32 UBX-22008968 for HPG 1.3x).
std::uint8_t firmware_of(const UbxSettings& u) {
  for (const std::string& e : u.extensions)
    if (e.starts_with("FWVER=HPG 1.3")) return kFwHpg132;
  return kFwHpg113;
}

}  // namespace

UbxDevice::UbxDevice(const GnssProfile& profile, ReceiverMode mode, const NavData& nav)
    : profile_(profile),
      mode_(mode),
      nav_(nav),
      protocol27_(profile.ubx->protver >= "27"),
      keys_{item("CFG-RATE-MEAS"), item("CFG-RATE-NAV"), item("CFG-RATE-TIMEREF"),
            {item("CFG-TMODE-MODE"), item("CFG-TMODE-SVIN_MIN_DUR"), item("CFG-TMODE-SVIN_ACC_LIMIT")}},
      config_(firmware_of(*profile.ubx), profile_defaults(profile)),
      legacy_(protocol27_) {
  // Room for every satellite: copying and refilling the epoch's lists never allocates.
  last_fix_.satellites.reserve(kDefinedSatellites);
  nmea_fix_.satellites.reserve(kDefinedSatellites);
  last_meas_.sats.reserve(kDefinedSatellites);
  lists_.svinfo.channels.reserve(kDefinedSatellites);
  lists_.sat.svs.reserve(kDefinedSatellites);
  lists_.rawx.meas.reserve(kDefinedSatellites);
  lists_.measx.svs.reserve(kDefinedSatellites);
  lists_.rf.blocks.reserve(2);
  lists_.sig.signals.reserve(2 * kDefinedSatellites);
  lists_.orb.svs.reserve(255);
  lists_.comms.ports.reserve(kNumPorts);
  lists_.io.ports.reserve(kNumPorts);
  status_.hw_version = profile_.ubx->hw_version;
  status_.bands = profile_.bands;
  // Messages without a CFG-MSGOUT item on this part (u-blox 8 ones): the profile's rates, on
  // the ports profile_defaults() sets.
  const auto keep = [&](MsgId id, int rate) {
    if (msgout_key(id, kPortUart1)) return;
    for (std::uint8_t port : kPortsButUart2)
      other_rates_[key(id)][port] = static_cast<std::uint8_t>(rate);
  };
  for (const auto& [name, rate] : profile_.ubx->messages)
    if (const MessageInfo* m = find_message(name)) keep(m->id, rate);
  for (const auto& [name, rate] : profile_.sentences)
    for (const auto& [nid, n] : kNmeaIds)
      if (name == n) keep({kClassNmea, nid}, rate);
  refresh();
  scratch_.reserve(8192);
}

namespace {

// The CFG-MSGOUT item of a message on a port, by name (0: none).
std::uint32_t msgout_item(MsgId id, std::uint8_t port) {
  const std::string n = msgout_name(id);
  return n.empty() ? 0 : item("CFG-MSGOUT-" + n + "_" + kPortNames[port]);
}

// Those of the messages refresh() reads the rates of, looked up once (the key database is
// searched by name): by port, the outputs in the order of ubx_outputs(), then kNmeaIds.
using MsgoutItems = std::array<std::array<std::uint32_t, kMaxUbxOutputs + std::size(kNmeaIds)>, kReceiverPorts>;
const MsgoutItems& cached_msgout_items() {
  static const MsgoutItems items = [] {
    MsgoutItems k{};
    const std::span<const UbxOutput> outs = ubx_outputs();
    for (std::uint8_t p = 0; p < kReceiverPorts; ++p) {
      for (std::size_t i = 0; i < outs.size(); ++i) k[p][i] = msgout_item(outs[i].id, p);
      for (std::size_t i = 0; i < std::size(kNmeaIds); ++i)
        k[p][kMaxUbxOutputs + i] = msgout_item({kClassNmea, kNmeaIds[i].first}, p);
    }
    return k;
  }();
  return items;
}

}  // namespace

std::uint32_t UbxDevice::msgout_key(MsgId id, std::uint8_t port) const {
  if (port >= kReceiverPorts) return 0;
  const std::span<const UbxOutput> outs = ubx_outputs();
  const auto& cached = cached_msgout_items()[port];
  for (std::size_t i = 0; i < outs.size(); ++i)
    if (outs[i].id == id) return cached[i];
  if (id.cls == kClassNmea)
    for (std::size_t i = 0; i < std::size(kNmeaIds); ++i)
      if (kNmeaIds[i].first == id.id) return cached[kMaxUbxOutputs + i];
  return msgout_item(id, port);
}

// The configuration in the form the output needs, after a change (not in the steady loop: a
// change comes from a client's command).
void UbxDevice::refresh() {
  if (!stale_ && config_.generation() == seen_generation_) return;
  seen_generation_ = config_.generation();
  stale_ = false;
  period_ns_ = static_cast<std::int64_t>(std::max<std::uint64_t>(config_.get(keys_.rate_meas), 1) *
                                         std::max<std::uint64_t>(config_.get(keys_.rate_nav), 1)) *
               1'000'000;
  time_ref_ = config_.get(keys_.rate_timeref);
  status_.outfil_pdop = static_cast<double>(config_.get(item("CFG-NAVSPG-OUTFIL_PDOP"))) * 0.1;
  status_.outfil_pacc_m = static_cast<double>(config_.get(item("CFG-NAVSPG-OUTFIL_PACC")));
  const auto flag = [&](std::uint32_t id, bool fallback) { return id ? config_.get(id) != 0 : fallback; };
  engine_ = engine_settings_of(config_);
  // The systems tracked: the F9's CFG-SIGNAL items, the u-blox 8's CFG-GNSS (power-up: GPS,
  // SBAS, QZSS, GLONASS; m8_power_up_gnss), both seen as CFG-GNSS.
  const CfgGnss gnss = current_cfg_gnss();
  engine_.systems = systems_of(gnss);
  if (protocol27_) engine_.l2_systems = systems_of(gnss, 0x30);
  // Switches the outputs follow: configuration items on the F9, the legacy CFG-ITFM (config
  // bit 31 "enable") and CFG-ODO (flags bit 0 "useODO") on the u-blox 8 (UBX-13003221).
  if (protocol27_) {
    refresh_time_mode();
    status_.jamming_monitor = flag(item("CFG-ITFM-ENABLE"), true);
    if (const std::uint32_t bb = item("CFG-ITFM-BBTHRESHOLD")) status_.itfm_bb_threshold_db = static_cast<double>(config_.get(bb));
    if (const std::uint32_t cw = item("CFG-ITFM-CWTHRESHOLD")) status_.itfm_cw_threshold_db = static_cast<double>(config_.get(cw));
    status_.odometer = flag(item("CFG-ODO-USE_ODO"), false);
  } else {
    CfgItfm itfm;
    CfgOdo odo;
    const bool itfm_set = decode(legacy_.current(kCfgItfm), itfm);
    status_.jamming_monitor = itfm_set && (itfm.config & CfgItfm::kEnable);
    if (itfm_set) {  // bbThreshold bits 0..3, cwThreshold bits 4..8 (UBX-13003221 "UBX-CFG-ITFM")
      status_.itfm_bb_threshold_db = static_cast<double>(itfm.config & 0xF);
      status_.itfm_cw_threshold_db = static_cast<double>(itfm.config >> 4 & 0x1F);
    }
    status_.odometer = decode(legacy_.current(kCfgOdo), odo) && (odo.flags & CfgOdo::kUseOdo);
  }
  // MON-GNSS enabled bits: GPS 0, GLONASS 1, BeiDou 2, Galileo 3 (F9 5.13.2).
  const auto enabled = [&](GnssSystem g) { return (engine_.systems & system_bit(g)) != 0; };
  status_.gnss_enabled = static_cast<std::uint8_t>((enabled(GnssSystem::kGps) ? 0x01 : 0) |
                                                   (enabled(GnssSystem::kGlonass) ? 0x02 : 0) |
                                                   (enabled(GnssSystem::kBeidou) ? 0x04 : 0) |
                                                   (enabled(GnssSystem::kGalileo) ? 0x08 : 0));
  // NMEA version and main talker ID: the F9's CFG-NMEA-PROTVER and -MAINTALKERID, the u-blox 8's
  // legacy CFG-NMEA nmeaVersion (BCD: 0x40 is 4.0, its power-up value) and mainTalkerId
  // (UBX-13003221 "UBX-CFG-NMEA"). Talker 0: as the GNSS configuration says (the profile's),
  // 1 GP, 2 GL, 3 GN, 4 GA, 5 GB, 7 GQ.
  std::uint64_t talker = 0;
  nmea_version_.reset();
  if (protocol27_) {
    nmea_version_ = static_cast<int>(config_.get(item("CFG-NMEA-PROTVER")));
    talker = config_.get(item("CFG-NMEA-MAINTALKERID"));
  } else if (CfgNmea m; decode(legacy_.current(kCfgNmea), m)) {
    nmea_version_ = (m.nmea_version >> 4) * 10 + (m.nmea_version & 0xF);
    talker = m.main_talker_id;
  }
  static constexpr const char* kTalkers[] = {"", "GP", "GL", "GN", "GA", "GB", "", "GQ"};
  // Not overridden: the talker of the systems enabled now (GP after CFG-GNSS leaves GPS alone),
  // or the profile's own when it names one.
  const std::string_view profile_auto = nmea::main_talker(profile_.systems);
  const std::string automatic = profile_.talker == profile_auto
                                    ? std::string(nmea::main_talker(profile_.systems & engine_.systems))
                                    : profile_.talker;
  talker_ = talker < std::size(kTalkers) && *kTalkers[talker] != '\0' ? kTalkers[talker] : automatic;
  // High precision mode "cannot be used while in NMEA compatibility mode or when NMEA output is
  // limited to 82 characters" (ZED-F9P integration manual UBX-18010802 3.1.4.5); the u-blox 8
  // profile's protocol 18 has no high precision mode (UBX-13003221 CFG-NMEA flags: highPrec
  // "not supported in protocol versions < 20.01").
  const bool high_precision = protocol27_ && flag(item("CFG-NMEA-HIGHPREC"), false) &&
                              !flag(item("CFG-NMEA-COMPAT"), false) && !flag(item("CFG-NMEA-LIMIT82"), false);
  for (std::uint8_t p = 0; p < kReceiverPorts; ++p) {
    PortSettings& s = ports_[p];
    s.in_ubx = flag(proto_item(p, true, "UBX"), true);
    s.in_nmea = flag(proto_item(p, true, "NMEA"), true);
    s.out_ubx = flag(proto_item(p, false, "UBX"), true);
    s.out_nmea = flag(proto_item(p, false, "NMEA"), true);
    const int baud = baud_item(p) ? static_cast<int>(config_.get(baud_item(p))) : 0;
    if (s.baud != 0 && baud != s.baud) pending_baud_[p] = baud;  // after the acknowledgement
    s.baud = baud;
    const std::span<const UbxOutput> outs = ubx_outputs();
    for (std::size_t i = 0; i < outs.size(); ++i)
      s.ubx_rates[i] = static_cast<std::uint8_t>(rate(outs[i].id, p));
    GnssProfile np = profile_;
    np.talker = talker_;
    np.sentences.clear();
    // The profile's order of sentences, then any other one a client switched on.
    for (const auto& [nid, n] : kNmeaIds)
      if (const int r = rate({kClassNmea, nid}, p); r > 0) np.sentences.emplace_back(n, r);
    std::stable_sort(np.sentences.begin(), np.sentences.end(), [&](const auto& a, const auto& b) {
      const auto rank = [&](const std::string& n) {
        for (std::size_t i = 0; i < profile_.sentences.size(); ++i)
          if (profile_.sentences[i].first == n) return i;
        return profile_.sentences.size();
      };
      return rank(a.first) < rank(b.first);
    });
    s.nmea = std::make_unique<NmeaOutput>(np, mode_, nmea_version_, high_precision);
  }
}

// The time mode (F9 interface description CFG-TMODE-*; the u-blox 8 profile is a standard
// precision part without it): survey-in (mode 1) starts anew with new settings, fixed (2) and
// disabled (0) have none. Fixed mode's position is the ARP's, ECEF (CFG-TMODE-ECEF_X/Y/Z in cm
// plus the _HP parts in 0.1 mm) or LLH (CFG-TMODE-LAT/LON in 1e-7 deg plus _HP in 1e-9 deg,
// HEIGHT in cm plus _HP in 0.1 mm above the WGS 84 ellipsoid), accurate to
// CFG-TMODE-FIXED_POS_ACC (0.1 mm).
void UbxDevice::refresh_time_mode() {
  constexpr std::uint64_t kSurveyIn = 1, kFixed = 2;
  std::array<std::uint64_t, 3> settings{};
  for (std::size_t i = 0; i < settings.size(); ++i) settings[i] = config_.get(keys_.tmode[i]);
  fixed_position_.reset();
  if (settings[0] == kFixed) {
    const auto get = [&](const char* key, std::int64_t bits) {  // signed items as their two's complement
      const std::uint64_t v = config_.get(item(key));
      return static_cast<double>(bits == 8 ? std::int64_t{static_cast<std::int8_t>(v)}
                                           : std::int64_t{static_cast<std::int32_t>(v)});
    };
    const auto coordinate = [&](const char* key, double whole_unit, const std::string& hp_key, double hp_unit) {
      return get(key, 32) * whole_unit + get(hp_key.c_str(), 8) * hp_unit;
    };
    Vec3 p = Vec3::Zero();
    if (config_.get(item("CFG-TMODE-POS_TYPE")) == 1) {
      p = ecef_from_geodetic({coordinate("CFG-TMODE-LAT", 1e-7, "CFG-TMODE-LAT_HP", 1e-9),
                              coordinate("CFG-TMODE-LON", 1e-7, "CFG-TMODE-LON_HP", 1e-9),
                              coordinate("CFG-TMODE-HEIGHT", 1e-2, "CFG-TMODE-HEIGHT_HP", 1e-4)});
    } else {
      for (int i = 0; i < 3; ++i) {
        const std::string axis = std::string("CFG-TMODE-ECEF_") + "XYZ"[i];
        p[i] = coordinate(axis.c_str(), 1e-2, axis + "_HP", 1e-4);
      }
    }
    fixed_position_ = FixedPosition{p, static_cast<double>(config_.get(item("CFG-TMODE-FIXED_POS_ACC"))) * 1e-4};
  }
  if (survey_settings_ == settings) return;
  survey_settings_ = settings;
  if (settings[0] == kSurveyIn)
    survey_.start({.min_duration_s = static_cast<double>(settings[1]),
                   .acc_limit_m = static_cast<double>(settings[2]) * 1e-4});  // 0.1 mm
  else
    survey_.stop();
  status_.svin = survey_.state();
}

std::optional<int> UbxDevice::take_baud_change(ReceiverPort port) {
  auto& p = pending_baud_[static_cast<std::size_t>(port)];
  std::optional<int> b = p;
  p.reset();
  return b;
}

int UbxDevice::rate(MsgId id, std::uint8_t port) const {
  if (const std::uint32_t k = msgout_key(id, port)) return static_cast<int>(config_.get(k));
  const auto it = other_rates_.find(key(id));
  return it == other_rates_.end() || port >= kNumPorts ? 0 : it->second[port];
}

void UbxDevice::set_keys(std::initializer_list<CfgKeyValue> values) {
  std::vector<CfgKeyValue> v;
  for (const CfgKeyValue& kv : values)
    if (kv.key_id) v.push_back(kv);
  config_.set_ram(v);
}

void UbxDevice::set_rate(MsgId id, std::uint8_t port, int r) {
  const auto rate8 = static_cast<std::uint8_t>(std::clamp(r, 0, 255));
  if (const std::uint32_t k = msgout_key(id, port)) return set_keys({{k, rate8}});
  if (port < kNumPorts) other_rates_[key(id)][port] = rate8;
  stale_ = true;  // not in the database: refresh() must still run
}

UbxDeviceCounters UbxDevice::counters() const {
  UbxDeviceCounters c = counters_;
  for (const Parser& p : parsers_) {
    c.checksum_errors += p.counters().checksum_errors;
    c.too_long += p.counters().too_long;
    c.junk_bytes += p.counters().junk_bytes;
  }
  for (const pubx::NmeaInputReader& r : nmea_in_)
    c.nmea_ignored += r.counters().checksum_errors + r.counters().malformed + r.counters().overlong;
  return c;
}

// ---- Input: configuration and polls ------------------------------------------------------

void UbxDevice::receive(std::span<const std::uint8_t> bytes, ReceiverPort port, std::string& replies) {
  const auto p = static_cast<std::uint8_t>(port);
  scratch_.clear();
  Parser& parser = parsers_[p];
  UbxPortTraffic& traffic = status_.ports[p];
  traffic.rx_bytes += static_cast<std::uint32_t>(bytes.size());
  const auto on_ubx = [&](Parser::Result r) {
    if (r != Parser::Result::kFrame) return;
    ++counters_.frames;
    ++traffic.msgs[0];
    traffic.parsed_bytes += static_cast<std::uint32_t>(parser.payload().size() + 8);
    if (ports_[p].in_ubx) handle(parser.cls(), parser.id(), parser.payload(), p, scratch_);
    refresh();
  };
  // Byte by byte through both readers, so that commands take effect in the order they came.
  for (const std::uint8_t& b : bytes) {
    parser.feed(std::span<const std::uint8_t>(&b, 1), on_ubx);
    if (const std::optional<std::string_view> s = nmea_in_[p].feed(b)) {
      ++traffic.msgs[1];
      traffic.parsed_bytes += static_cast<std::uint32_t>(s->size());
      receive_nmea(*s, p, scratch_);
    }
  }
  traffic.tx_bytes += static_cast<std::uint32_t>(scratch_.size());
  replies.append(reinterpret_cast<const char*>(scratch_.data()), scratch_.size());
}

void UbxDevice::ack(MsgId msg, Bytes& out) {
  ++counters_.acks;
  append(AckAck{msg.cls, msg.id}, out);
}

void UbxDevice::nak(MsgId msg, Bytes& out) {
  ++counters_.naks;
  append(AckNak{msg.cls, msg.id}, out);
}

// The commands the receiver takes: a poll (empty payload) answered by `poll`, anything else
// (and polls of messages without `poll`) handled by `set`, which acknowledges itself.
struct UbxDevice::Command {
  enum Parts : std::uint8_t { kBoth, kF9, kM8 };
  MsgId id;
  // kF9: protocol 27+ only (the configuration interface, UBX-18010854 section 6; UPD-SOS, the
  // M8 profile being a ROM part without flash); kM8: u-blox 8 only (the AID messages).
  Parts parts;
  void (UbxDevice::*poll)(std::uint8_t port, Bytes& out);
  void (UbxDevice::*set)(Payload payload, std::uint8_t port, Bytes& out);
};

const UbxDevice::Command UbxDevice::kCommands[] = {
    {kMonVer, Command::kBoth, &UbxDevice::poll_mon_ver, nullptr},
    {kMonGnss, Command::kBoth, &UbxDevice::poll_mon_gnss, nullptr},
    {kMonPatch, Command::kBoth, &UbxDevice::poll_mon_patch, nullptr},
    {kSecUniqid, Command::kBoth, &UbxDevice::poll_sec_uniqid, nullptr},
    {kNavResetodo, Command::kBoth, nullptr, &UbxDevice::handle_nav_resetodo},
    {kAidIni, Command::kM8, &UbxDevice::poll_aid_ini, nullptr},
    {kAidHui, Command::kM8, &UbxDevice::poll_aid_hui, nullptr},
    {kAidAlm, Command::kM8, &UbxDevice::poll_aid_alm, &UbxDevice::handle_aid_alm},
    {kAidEph, Command::kM8, &UbxDevice::poll_aid_eph, &UbxDevice::handle_aid_eph},
    {kAidAop, Command::kM8, &UbxDevice::poll_aid_aop, &UbxDevice::handle_aid_aop},
    {kMgaDbd, Command::kBoth, &UbxDevice::poll_mga_dbd, nullptr},
    {kUpdSos, Command::kF9, &UbxDevice::poll_upd_sos, &UbxDevice::handle_upd_sos},
    {kCfgPrt, Command::kBoth, nullptr, &UbxDevice::handle_cfg_prt},
    {kCfgMsg, Command::kBoth, nullptr, &UbxDevice::handle_cfg_msg},
    {kCfgRate, Command::kBoth, &UbxDevice::poll_cfg_rate, &UbxDevice::handle_cfg_rate},
    {kCfgNav5, Command::kBoth, &UbxDevice::poll_cfg_nav5, &UbxDevice::handle_cfg_nav5},
    {kCfgTmode3, Command::kF9, &UbxDevice::poll_cfg_tmode3, &UbxDevice::handle_cfg_tmode3},
    {kCfgInf, Command::kF9, nullptr, &UbxDevice::handle_cfg_inf},
    {kCfgItfm, Command::kF9, &UbxDevice::poll_cfg_itfm, &UbxDevice::handle_cfg_itfm},
    {kCfgOdo, Command::kF9, &UbxDevice::poll_cfg_odo, &UbxDevice::handle_cfg_odo},
    {kCfgNmea, Command::kF9, &UbxDevice::poll_cfg_nmea, &UbxDevice::handle_cfg_nmea},
    {kCfgTp5, Command::kF9, nullptr, &UbxDevice::handle_cfg_tp5},
    {kCfgGnss, Command::kBoth, &UbxDevice::poll_cfg_gnss, &UbxDevice::handle_cfg_gnss},
    {kCfgCfg, Command::kBoth, nullptr, &UbxDevice::handle_cfg_cfg},
    {kCfgRst, Command::kBoth, nullptr, &UbxDevice::handle_cfg_rst},
    {kCfgValset, Command::kF9, nullptr, &UbxDevice::handle_valset},
    {kCfgValget, Command::kF9, nullptr, &UbxDevice::handle_valget},
    {kCfgValdel, Command::kF9, nullptr, &UbxDevice::handle_valdel},
};

void UbxDevice::handle(std::uint8_t cls, std::uint8_t id, Payload p, std::uint8_t port, Bytes& out) {
  const MsgId msg{cls, id};
  // Any CFG message but VALSET and VALDEL cancels a started transaction (UBX-CFG-VALSET notes).
  if (cls == kClassCfg && !(msg == kCfgValset) && !(msg == kCfgValdel)) config_.cancel_transaction();
  for (const Command& c : kCommands) {
    if (!(c.id == msg) || (c.parts == (protocol27_ ? Command::kM8 : Command::kF9))) continue;
    if (p.empty() && c.poll) {
      ++counters_.polls;
      return (this->*c.poll)(port, out);
    }
    if (c.set) return (this->*c.set)(p, port, out);
    break;
  }
  if (cls == kClassMga && !p.empty()) return acknowledge_aiding(msg, p, out);
  if (cls != kClassCfg) {
    // A poll of an output message is answered with the latest epoch's message.
    if (p.empty() && output_message(msg, out)) ++counters_.polls;
    return;
  }
  // The legacy messages navemu keeps without modelling: a poll is answered with the message
  // and then acknowledged, a set acknowledged or refused (UBX-13003221 32.5 "UBX Message Flow").
  if (legacy_.has(msg) && legacy_.handle(msg, p, out)) {
    stale_ = true;  // the u-blox 8's switches are legacy settings (refresh())
    return ack(msg, out);
  }
  nak(msg, out);  // a configuration message this receiver does not have, or a form it refuses
}

namespace {
// The CFG-INFMSG item of a protocol (0 UBX, 1 NMEA) on a port.
std::uint32_t infmsg_key(std::uint8_t protocol, std::uint8_t port) {
  return item(std::string("CFG-INFMSG-") + (protocol == 1 ? "NMEA_" : "UBX_") + kPortNames[port]);
}
}  // namespace

// INF-* as UBX and as NMEA TXT, each where the port's INF mask for that protocol has the type's
// bit and the port outputs the protocol (F9 interface description CFG-INFMSG-UBX_/NMEA_<port>;
// u-blox 8: CFG-INF, the protocol 0 and 1 blocks' infMsgMask by port ID).
void UbxDevice::inform(std::uint8_t port, std::uint8_t type, std::string_view text, Bytes& out) {
  const auto mask = [&](bool nmea_protocol) -> unsigned {
    if (protocol27_) return static_cast<unsigned>(config_.get(infmsg_key(nmea_protocol ? 1 : 0, port)));
    CfgInf m;
    return decode(legacy_.current(kCfgInf, static_cast<std::uint8_t>(nmea_protocol ? 1 : 0)), m) && !m.blocks.empty()
               ? m.blocks[0].inf_msg_mask[port]
               : 0u;
  };
  const unsigned bit = 1u << type;
  if (ports_[port].out_ubx && (mask(false) & bit))
    append_frame(kClassInf, type, {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}, out);
  if (ports_[port].out_nmea && (mask(true) & bit)) {
    std::string line;
    nmea::encode(nmea::TxtFields{talker_, 1, 1, type, text}, nmea::Format::ublox(), line);
    out.insert(out.end(), line.begin(), line.end());
  }
}

void UbxDevice::poll_mon_ver(std::uint8_t, Bytes& out) {
  const UbxSettings& u = *profile_.ubx;
  append(MonVer{u.sw_version, u.hw_version, u.extensions}, out);
}

// MON-GNSS (M8 32.16.2, F9 5.13.2): GPS, GLONASS, BeiDou and Galileo supported; the defaults of
// the u-blox 8 (GPS + GLONASS, 3 at once) and of the F9 (all four at once).
void UbxDevice::poll_mon_gnss(std::uint8_t, Bytes& out) {
  MonGnss m;
  m.supported = 0x0F;
  m.default_gnss = protocol27_ ? 0x0F : 0x03;
  m.enabled = status_.gnss_enabled;
  m.simultaneous = protocol27_ ? 4 : 3;
  append(m, out);
}

// MON-PATCH (M8 32.16.7, F9 5.13.8): no patches installed.
void UbxDevice::poll_mon_patch(std::uint8_t, Bytes& out) { append(MonPatch{}, out); }

// SEC-UNIQID (M8 32.19.1, F9 5.16): a 40-bit chip ID, fixed per profile (FNV-1a of its MON-VER
// strings), so that a client sees the same receiver every run.
void UbxDevice::poll_sec_uniqid(std::uint8_t, Bytes& out) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const std::string* s : {&profile_.ubx->sw_version, &profile_.ubx->hw_version})
    for (const char c : *s) h = (h ^ static_cast<std::uint8_t>(c)) * 0x100000001b3ULL;
  SecUniqid m;
  for (std::size_t i = 0; i < m.unique_id.size(); ++i) m.unique_id[i] = static_cast<std::uint8_t>(h >> (8 * i));
  append(m, out);
}

// NAV-RESETODO (M8 32.17.17, F9 5.14.13): the odometer's distance back to 0, acknowledged.
void UbxDevice::handle_nav_resetodo(Payload p, std::uint8_t, Bytes& out) {
  if (!p.empty()) return nak(kNavResetodo, out);
  status_.odo_distance_m = 0.0;
  ack(kNavResetodo, out);
}

// ---- Aiding data, the navigation database and its backup (emulator/ubx_aiding.hpp) ---------
// AID-* (u-blox 8): a poll of all 32 GPS satellites or, with one byte, of one; the aiding input
// itself is taken without effect (navemu's navigation data are the run's) and not acknowledged.

void UbxDevice::poll_aid_ini(std::uint8_t, Bytes& out) { append_aid_ini(last_fix_, last_meas_, out); }

void UbxDevice::poll_aid_hui(std::uint8_t, Bytes& out) { append_aid_hui(nav_, last_fix_.t, out); }

void UbxDevice::poll_aid_alm(std::uint8_t, Bytes& out) {
  for (int n = 1; n <= kAidSatellites; ++n) append_aid_alm(n, nav_, last_fix_.t, out);
}

void UbxDevice::poll_aid_eph(std::uint8_t, Bytes& out) {
  for (int n = 1; n <= kAidSatellites; ++n) append_aid_eph(n, last_meas_, out);
}

// AID-AOP (u-blox 8): AssistNow Autonomous is off, so no satellite has its data, and the answer
// per satellite is "the corresponding poll request message" (UBX-AID-AOP).
void UbxDevice::poll_aid_aop(std::uint8_t, Bytes& out) {
  for (int n = 1; n <= kAidSatellites; ++n) append(AidAopPoll{static_cast<std::uint8_t>(n)}, out);
}

// The one-satellite polls of AID-ALM, AID-EPH and AID-AOP; a satellite outside 1..32 gets nothing.
std::optional<int> UbxDevice::aid_poll_svid(Payload p) {
  if (p.size() != 1 || p[0] < 1 || p[0] > kAidSatellites) return std::nullopt;
  ++counters_.polls;
  return p[0];
}

void UbxDevice::handle_aid_alm(Payload p, std::uint8_t, Bytes& out) {
  if (const std::optional<int> n = aid_poll_svid(p)) append_aid_alm(*n, nav_, last_fix_.t, out);
}

void UbxDevice::handle_aid_eph(Payload p, std::uint8_t, Bytes& out) {
  if (const std::optional<int> n = aid_poll_svid(p)) append_aid_eph(*n, last_meas_, out);
}

void UbxDevice::handle_aid_aop(Payload p, std::uint8_t, Bytes& out) {
  if (const std::optional<int> n = aid_poll_svid(p)) append(AidAopPoll{static_cast<std::uint8_t>(*n)}, out);
}

void UbxDevice::poll_mga_dbd(std::uint8_t, Bytes& out) { append_mga_dbd_dump(last_meas_, out); }

// Assistance data in (MGA-GPS, -GAL, -BDS, -QZSS, -GLO, -ANO, -INI, and MGA-DBD entries sent
// back): acknowledged with MGA-ACK-DATA0 when acknowledgements are on (UBX-18010854 5.12.1,
// 5.12.3.2; CFG-NAVSPG-ACKAIDING, or a CFG-NAVX5 that sets ackAiding, UBX-13003221 32.10.16),
// as accepted (type 1, infoCode 0), echoing the message ID and its first four payload bytes.
// navemu's receiver does not use the data: its start-up is the profile's. Other MGA IDs are
// not input messages (MGA-ACK is the receiver's own; MGA-FLASH, the u-blox 8's flash upload,
// answers with its own MGA-FLASH-ACK and is not modelled) and get nothing.
void UbxDevice::acknowledge_aiding(MsgId msg, Payload p, Bytes& out) {
  static constexpr std::uint8_t kInputs[] = {0x00, 0x02, 0x03, 0x05, 0x06, 0x20, 0x40, kMgaDbd.id};
  if (std::find(std::begin(kInputs), std::end(kInputs), msg.id) == std::end(kInputs)) return;
  constexpr std::uint16_t kAckAid = 1u << 10;  // CFG-NAVX5 mask1: apply ackAiding
  CfgNavx5 navx5;
  const bool legacy_on = decode(legacy_.current(kCfgNavx5), navx5) && (navx5.mask1 & kAckAid) && navx5.ack_aiding;
  if (!legacy_on && !(protocol27_ && config_.get(item("CFG-NAVSPG-ACKAIDING")) != 0)) return;
  MgaAck ack;
  ack.msg_id = msg.id;
  for (std::size_t i = 0; i < 4 && i < p.size(); ++i) ack.msg_payload_start |= std::uint32_t{p[i]} << (8 * i);
  append(ack, out);
}

// UPD-SOS (UBX-18010854 5.18.1): the poll is answered with whether the last start restored a
// backup; "create" makes one and is answered with the creation acknowledgement; "clear" removes
// it, with no answer described.
void UbxDevice::poll_upd_sos(std::uint8_t, Bytes& out) {
  UpdSos m;
  m.cmd = UpdSos::kRestored;
  m.response = sos_restored_ ? 2 : 3;  // restored from backup / not restored (no backup)
  append(m, out);
}

void UbxDevice::handle_upd_sos(Payload p, std::uint8_t, Bytes& out) {
  UpdSosCommand c;
  if (!decode(p, c)) return;
  if (c.cmd == UpdSosCommand::kCreate) {
    sos_backup_ = true;
    UpdSos m;
    m.cmd = UpdSos::kCreationAck;
    m.response = 1;  // acknowledged
    append(m, out);
  } else if (c.cmd == UpdSosCommand::kClear) {
    sos_backup_ = false;
  }
}


// CFG-PRT: one or more 20-byte port blocks (UBX-18010854 "UBX-CFG-PRT": several configurations
// may be concatenated in one input message), each onto its port's configuration items.
void UbxDevice::handle_cfg_prt(Payload p, std::uint8_t port, Bytes& out) {
  CfgPrtPoll poll;
  if (decode(p, poll)) {
    const std::uint8_t which = poll.has_port_id ? poll.port_id : port;
    if (which >= kReceiverPorts) return nak(kCfgPrt, out);
    ++counters_.polls;
    CfgPrt r;
    r.port_id = which;
    const bool uart = which == kPortUart1 || which == kPortUart2;
    r.mode = uart ? CfgPrt::kMode8N1 : 0;
    r.baud_rate = uart ? static_cast<std::uint32_t>(ports_[which].baud) : 0;
    const PortSettings& s = ports_[which];
    const auto mask = [&](bool ubx_on, bool nmea_on, std::uint32_t rtcm3) {
      return static_cast<std::uint16_t>((ubx_on ? kProtoUbx : 0) | (nmea_on ? kProtoNmea : 0) |
                                        (rtcm3 && config_.get(rtcm3) ? kProtoRtcm3 : 0));
    };
    r.in_proto_mask = mask(s.in_ubx, s.in_nmea, proto_item(which, true, "RTCM3X"));
    r.out_proto_mask = mask(s.out_ubx, s.out_nmea, proto_item(which, false, "RTCM3X"));
    append(r, out);
    return ack(kCfgPrt, out);
  }
  if (p.empty() || p.size() % CfgPrt::kPayloadSize != 0) return nak(kCfgPrt, out);
  std::vector<CfgKeyValue> values;
  for (std::size_t at = 0; at < p.size(); at += CfgPrt::kPayloadSize) {
    CfgPrt set;
    if (!decode(p.subspan(at, CfgPrt::kPayloadSize), set) || set.port_id >= kReceiverPorts)
      return nak(kCfgPrt, out);
    port_values(set.port_id, set.in_proto_mask, set.out_proto_mask, set.baud_rate, values);
  }
  if (!config_.set_ram(values)) return nak(kCfgPrt, out);
  ack(kCfgPrt, out);
}

void UbxDevice::port_values(std::uint8_t port, std::uint16_t in_mask, std::uint16_t out_mask, std::uint32_t baud,
                            std::vector<CfgKeyValue>& values) const {
  const auto flag = [&](bool in, const char* proto, std::uint16_t mask, std::uint16_t bit) {
    if (const std::uint32_t id = proto_item(port, in, proto)) values.push_back({id, (mask & bit) ? 1u : 0u});
  };
  flag(true, "UBX", in_mask, kProtoUbx);
  flag(true, "NMEA", in_mask, kProtoNmea);
  flag(true, "RTCM3X", in_mask, kProtoRtcm3);
  flag(false, "UBX", out_mask, kProtoUbx);
  flag(false, "NMEA", out_mask, kProtoNmea);
  flag(false, "RTCM3X", out_mask, kProtoRtcm3);
  if (const std::uint32_t b = baud_item(port); b && baud != 0) values.push_back({b, baud});
}

void UbxDevice::handle_cfg_msg(Payload p, std::uint8_t port, Bytes& out) {
  CfgMsgPoll poll;
  CfgMsgCurrentPort cur;
  CfgMsg all;
  if (decode(p, poll)) {
    ++counters_.polls;
    CfgMsg r;
    r.msg_class = poll.msg_class;
    r.msg_id = poll.msg_id;
    for (std::uint8_t q = 0; q < kNumPorts; ++q)
      r.rate[q] = static_cast<std::uint8_t>(rate({poll.msg_class, poll.msg_id}, q));
    append(r, out);
    return ack(kCfgMsg, out);
  }
  // The 3-byte form sets the rate on the port the command came in on, the 8-byte form on all.
  std::optional<MsgId> change;
  if (decode(p, cur)) change = MsgId{cur.msg_class, cur.msg_id};
  else if (decode(p, all)) change = MsgId{all.msg_class, all.msg_id};
  if (!change) return nak(kCfgMsg, out);
  const MsgId target = *change;
  // The receiver takes a rate for any message of its output classes (gpsd also sets e.g.
  // NAV-TIMELS and NMEA GBS); it sends those it produces. Other classes are refused.
  constexpr std::uint8_t kOutputClasses[] = {kClassNav, kClassRxm, kClassInf, kClassMon,
                                             kClassTim, kClassEsf, kClassHnr, kClassSec,
                                             kClassNmea, kClassPubx};
  if (std::find(std::begin(kOutputClasses), std::end(kOutputClasses), target.cls) == std::end(kOutputClasses))
    return nak(kCfgMsg, out);
  if (p.size() == CfgMsgCurrentPort::kPayloadSize)
    set_rate(target, port, cur.rate);
  else
    for (std::uint8_t q = 0; q < kReceiverPorts; ++q) set_rate(target, q, all.rate[q]);
  ack(kCfgMsg, out);
}

// CFG-RATE timeRef (UBX-13003221 "UBX-CFG-RATE"; F9 interface description
// CFG-RATE-TIMEREF): the measurements are aligned to the reference system's time. The epochs
// are whole periods of that system's time, which differs from GPS time by whole seconds
// (core/time.hpp), so its grid differs from GPS time's only for a period that does not divide
// that difference (e.g. 700 ms against UTC's 18 s).
std::int64_t UbxDevice::grid_offset_ns(GpsTime t) const {
  std::int64_t gps_minus_ref_s = 0;  // GPS (1) and Galileo (4) run together
  if (time_ref_ == CfgRate::kTimeRefUtc || time_ref_ == CfgRate::kTimeRefGlonass)
    gps_minus_ref_s = leap_seconds_at_gps(t, nav_.leap_seconds) -
                      (time_ref_ == CfgRate::kTimeRefGlonass ? kGlonassMinusUtc_s : 0);
  else if (time_ref_ == CfgRate::kTimeRefBeidou)
    gps_minus_ref_s = kGpsMinusBdt_s;
  const std::int64_t r = gps_minus_ref_s * kNsPerS % period_ns_;
  return r < 0 ? r + period_ns_ : r;
}

void UbxDevice::poll_cfg_rate(std::uint8_t, Bytes& out) {
  append(CfgRate{static_cast<std::uint16_t>(config_.get(keys_.rate_meas)),
                 static_cast<std::uint16_t>(config_.get(keys_.rate_nav)),
                 static_cast<std::uint16_t>(config_.get(keys_.rate_timeref))},
         out);
  ack(kCfgRate, out);
}

void UbxDevice::handle_cfg_rate(Payload p, std::uint8_t, Bytes& out) {
  CfgRate r;
  // Measurement rate 25 Hz at most (40 ms), navigation rate at least one measurement.
  if (!decode(p, r) || r.meas_rate_ms < 40 || r.nav_rate_cycles < 1 || r.nav_rate_cycles > 127 ||
      r.time_ref > CfgRate::kTimeRefGalileo)
    return nak(kCfgRate, out);
  set_keys({{keys_.rate_meas, r.meas_rate_ms}, {keys_.rate_nav, r.nav_rate_cycles}, {keys_.rate_timeref, r.time_ref}});
  ack(kCfgRate, out);
}

// CFG-NAV5's fields are configuration items (F9 interface description, "Legacy UBX-CFG message
// fields reference"); the mask bit that applies each is the u-blox 8's (UBX-13003221 CFG-NAV5).
namespace {
struct Nav5Field {
  std::uint16_t mask_bit;
  const char* key_name;
  std::uint64_t (*get)(const CfgNav5&);  // the field as the item's raw value
  void (*set)(CfgNav5&, std::uint64_t);
};
template <auto Member>
constexpr Nav5Field nav5_field(std::uint16_t bit, const char* key_name) {
  using T = std::remove_reference_t<decltype(std::declval<CfgNav5&>().*Member)>;
  using U = std::make_unsigned_t<T>;  // signed fields are held as their two's complement
  return {bit, key_name, [](const CfgNav5& n) -> std::uint64_t { return static_cast<U>(n.*Member); },
          [](CfgNav5& n, std::uint64_t v) { n.*Member = static_cast<T>(static_cast<U>(v)); }};
}
constexpr Nav5Field kNav5Fields[] = {
    nav5_field<&CfgNav5::dyn_model>(CfgNav5::kMaskDyn, "CFG-NAVSPG-DYNMODEL"),
    nav5_field<&CfgNav5::min_elev_deg>(CfgNav5::kMaskMinEl, "CFG-NAVSPG-INFIL_MINELEV"),
    nav5_field<&CfgNav5::fix_mode>(CfgNav5::kMaskPosFixMode, "CFG-NAVSPG-FIXMODE"),
    nav5_field<&CfgNav5::fixed_alt_cm>(CfgNav5::kMaskPosFixMode, "CFG-NAVSPG-CONSTR_ALT"),
    nav5_field<&CfgNav5::fixed_alt_var_1e4m2>(CfgNav5::kMaskPosFixMode, "CFG-NAVSPG-CONSTR_ALTVAR"),
    nav5_field<&CfgNav5::p_dop_0p1>(CfgNav5::kMaskPosMask, "CFG-NAVSPG-OUTFIL_PDOP"),
    nav5_field<&CfgNav5::p_acc_m>(CfgNav5::kMaskPosMask, "CFG-NAVSPG-OUTFIL_PACC"),
    nav5_field<&CfgNav5::t_dop_0p1>(CfgNav5::kMaskTimeMask, "CFG-NAVSPG-OUTFIL_TDOP"),
    nav5_field<&CfgNav5::t_acc_m>(CfgNav5::kMaskTimeMask, "CFG-NAVSPG-OUTFIL_TACC"),
    nav5_field<&CfgNav5::static_hold_thresh_cmps>(CfgNav5::kMaskStaticHoldMask, "CFG-MOT-GNSSSPEED_THRS"),
    nav5_field<&CfgNav5::static_hold_max_dist_m>(CfgNav5::kMaskStaticHoldMask, "CFG-MOT-GNSSDIST_THRS"),
    nav5_field<&CfgNav5::dgnss_timeout_s>(CfgNav5::kMaskDgpsMask, "CFG-NAVSPG-CONSTR_DGNSSTO"),
    nav5_field<&CfgNav5::cno_thresh_num_svs>(CfgNav5::kMaskCnoThreshold, "CFG-NAVSPG-INFIL_NCNOTHRS"),
    nav5_field<&CfgNav5::cno_thresh_dbhz>(CfgNav5::kMaskCnoThreshold, "CFG-NAVSPG-INFIL_CNOTHRS"),
    nav5_field<&CfgNav5::utc_standard>(CfgNav5::kMaskUtc, "CFG-NAVSPG-UTCSTANDARD"),
};
}  // namespace

void UbxDevice::poll_cfg_nav5(std::uint8_t, Bytes& out) {
  CfgNav5 n;
  n.mask = 0xFFFF;
  for (const Nav5Field& f : kNav5Fields) f.set(n, config_.get(item(f.key_name)));
  append(n, out);
  ack(kCfgNav5, out);
}

void UbxDevice::handle_cfg_nav5(Payload p, std::uint8_t, Bytes& out) {
  CfgNav5 n;
  if (!decode(p, n)) return nak(kCfgNav5, out);
  std::vector<CfgKeyValue> v;
  for (const Nav5Field& f : kNav5Fields)
    if (const std::uint32_t id = item(f.key_name); (n.mask & f.mask_bit) && id) v.push_back({id, f.get(n)});
  if (!config_.set_ram(v)) return nak(kCfgNav5, out);
  ack(kCfgNav5, out);
}

// CFG-TMODE3's fields are the CFG-TMODE-* items (F9 interface description, "Legacy UBX-CFG
// message fields reference"): flags bits 0..7 the mode, bit 8 the position as LLH rather than
// ECEF, which also picks the items the position fields are.
namespace {
struct Tmode3Position {
  const char *ecef_key, *llh_key;
  std::int32_t CfgTmode3::*whole;
  std::int8_t CfgTmode3::*hp;
  const char *ecef_hp_key, *llh_hp_key;
};
constexpr Tmode3Position kTmode3Position[] = {
    {"CFG-TMODE-ECEF_X", "CFG-TMODE-LAT", &CfgTmode3::ecef_x_or_lat, &CfgTmode3::ecef_x_or_lat_hp,
     "CFG-TMODE-ECEF_X_HP", "CFG-TMODE-LAT_HP"},
    {"CFG-TMODE-ECEF_Y", "CFG-TMODE-LON", &CfgTmode3::ecef_y_or_lon, &CfgTmode3::ecef_y_or_lon_hp,
     "CFG-TMODE-ECEF_Y_HP", "CFG-TMODE-LON_HP"},
    {"CFG-TMODE-ECEF_Z", "CFG-TMODE-HEIGHT", &CfgTmode3::ecef_z_or_alt_cm, &CfgTmode3::ecef_z_or_alt_hp_0p1mm,
     "CFG-TMODE-ECEF_Z_HP", "CFG-TMODE-HEIGHT_HP"},
};
constexpr std::pair<std::uint32_t CfgTmode3::*, const char*> kTmode3Unsigned[] = {
    {&CfgTmode3::fixed_pos_acc_0p1mm, "CFG-TMODE-FIXED_POS_ACC"},
    {&CfgTmode3::svin_min_dur_s, "CFG-TMODE-SVIN_MIN_DUR"},
    {&CfgTmode3::svin_acc_limit_0p1mm, "CFG-TMODE-SVIN_ACC_LIMIT"},
};
}  // namespace

void UbxDevice::poll_cfg_tmode3(std::uint8_t, Bytes& out) {
  const auto get = [&](const char* key) { return config_.get(item(key)); };
  CfgTmode3 m;
  const bool llh = get("CFG-TMODE-POS_TYPE") == 1;
  m.flags = static_cast<std::uint16_t>((get("CFG-TMODE-MODE") & CfgTmode3::kModeMask) | (llh ? CfgTmode3::kLla : 0));
  for (const Tmode3Position& f : kTmode3Position) {  // signed items are held as their two's complement
    m.*f.whole = static_cast<std::int32_t>(static_cast<std::uint32_t>(get(llh ? f.llh_key : f.ecef_key)));
    m.*f.hp = static_cast<std::int8_t>(static_cast<std::uint8_t>(get(llh ? f.llh_hp_key : f.ecef_hp_key)));
  }
  for (const auto& [member, key] : kTmode3Unsigned) m.*member = static_cast<std::uint32_t>(get(key));
  append(m, out);
  ack(kCfgTmode3, out);
}

// A set writes every item of the form it is in (all or nothing, refused like the items: an
// unknown mode, an HP part beyond +-99).
void UbxDevice::handle_cfg_tmode3(Payload p, std::uint8_t, Bytes& out) {
  CfgTmode3 m;
  if (!decode(p, m)) return nak(kCfgTmode3, out);
  const bool llh = (m.flags & CfgTmode3::kLla) != 0;
  std::vector<CfgKeyValue> v{{item("CFG-TMODE-MODE"), std::uint64_t{m.flags} & CfgTmode3::kModeMask},
                             {item("CFG-TMODE-POS_TYPE"), llh ? 1u : 0u}};
  for (const Tmode3Position& f : kTmode3Position) {
    v.push_back({item(llh ? f.llh_key : f.ecef_key), static_cast<std::uint32_t>(m.*f.whole)});
    v.push_back({item(llh ? f.llh_hp_key : f.ecef_hp_key), static_cast<std::uint8_t>(m.*f.hp)});
  }
  for (const auto& [member, key] : kTmode3Unsigned) v.push_back({item(key), m.*member});
  config_.set_ram(v) ? ack(kCfgTmode3, out) : nak(kCfgTmode3, out);
}

// On the F9 CFG-INF, CFG-ITFM, CFG-ODO, CFG-NMEA and CFG-TP5 are views of configuration items too (F9
// interface description, "Legacy UBX-CFG message fields reference"); the u-blox 8 keeps them as
// legacy settings (emulator/ubx_legacy_cfg.hpp).
//
// CFG-INF: a block per protocol (0 UBX, 1 NMEA) with the INF mask of each port ID, the items
// CFG-INFMSG-UBX_<port> / NMEA_<port>. The poll is the one-byte form naming the protocol; other
// protocols have no items and are refused.
void UbxDevice::handle_cfg_inf(Payload p, std::uint8_t, Bytes& out) {
  CfgInfPoll poll;
  if (decode(p, poll)) {
    if (poll.protocol_id > 1) return nak(kCfgInf, out);
    CfgInf m;
    CfgInfBlock& b = m.blocks.emplace_back();
    b.protocol_id = poll.protocol_id;
    for (std::uint8_t port = 0; port < kReceiverPorts; ++port)
      b.inf_msg_mask[port] = static_cast<std::uint8_t>(config_.get(infmsg_key(poll.protocol_id, port)));
    append(m, out);
    return ack(kCfgInf, out);
  }
  CfgInf m;
  if (!decode(p, m)) return nak(kCfgInf, out);
  std::vector<CfgKeyValue> v;
  for (const CfgInfBlock& b : m.blocks) {
    if (b.protocol_id > 1) return nak(kCfgInf, out);
    for (std::uint8_t port = 0; port < kReceiverPorts; ++port)
      v.push_back({infmsg_key(b.protocol_id, port), b.inf_msg_mask[port]});
  }
  config_.set_ram(v) ? ack(kCfgInf, out) : nak(kCfgInf, out);
}

// CFG-ITFM (UBX-13003221 "UBX-CFG-ITFM"): config holds bbThreshold bits 0..3, cwThreshold 4..8,
// the reserved algorithmBits 9..30 (0x16B156 "for correct settings") and enable bit 31;
// config2 the reserved generalBits 0..11 (0x31E), antSetting 12..13 and enable2 (the auxiliary
// band) bit 14.
namespace {
constexpr std::uint32_t kItfmAlgorithmBits = 0x16B156, kItfmGeneralBits = 0x31E;
}

void UbxDevice::poll_cfg_itfm(std::uint8_t, Bytes& out) {
  const auto get = [&](const char* key) { return static_cast<std::uint32_t>(config_.get(item(key))); };
  CfgItfm m;
  m.config = get("CFG-ITFM-BBTHRESHOLD") | get("CFG-ITFM-CWTHRESHOLD") << 4 | kItfmAlgorithmBits << 9 |
             get("CFG-ITFM-ENABLE") << 31;
  m.config2 = kItfmGeneralBits | get("CFG-ITFM-ANTSETTING") << 12 | get("CFG-ITFM-ENABLE_AUX") << 14;
  append(m, out);
  ack(kCfgItfm, out);
}

void UbxDevice::handle_cfg_itfm(Payload p, std::uint8_t, Bytes& out) {
  CfgItfm m;
  if (!decode(p, m)) return nak(kCfgItfm, out);
  const std::vector<CfgKeyValue> v{{item("CFG-ITFM-BBTHRESHOLD"), m.config & 0xF},
                                   {item("CFG-ITFM-CWTHRESHOLD"), m.config >> 4 & 0x1F},
                                   {item("CFG-ITFM-ENABLE"), m.config >> 31},
                                   {item("CFG-ITFM-ANTSETTING"), m.config2 >> 12 & 0x3},
                                   {item("CFG-ITFM-ENABLE_AUX"), m.config2 >> 14 & 0x1}};
  config_.set_ram(v) ? ack(kCfgItfm, out) : nak(kCfgItfm, out);
}

// Single-bit fields of a legacy message that are L items of their own: the bit and the item.
namespace {
struct BitItem {
  unsigned bit;
  const char* key;
};

std::uint32_t bits_of_items(const UbxConfig& config, std::span<const BitItem> bits) {
  std::uint32_t v = 0;
  for (const BitItem& b : bits) v |= static_cast<std::uint32_t>(config.get(item(b.key)) & 1) << b.bit;
  return v;
}

void items_of_bits(std::uint32_t value, std::span<const BitItem> bits, std::vector<CfgKeyValue>& v) {
  for (const BitItem& b : bits) v.push_back({item(b.key), value >> b.bit & 1u});
}
}  // namespace

// CFG-ODO (UBX-13003221 "UBX-CFG-ODO"): flags useODO bit 0, useCOG 1, outLPVel 2, outLPCog 3;
// odoCfg profile bits 0..2; then the COG filter's speed and accuracy limits and the two
// low-pass gains, each an item of its own.
namespace {
constexpr BitItem kOdoFlags[] = {
    {0, "CFG-ODO-USE_ODO"}, {1, "CFG-ODO-USE_COG"}, {2, "CFG-ODO-OUTLPVEL"}, {3, "CFG-ODO-OUTLPCOG"}};
constexpr std::pair<std::uint8_t CfgOdo::*, const char*> kOdoBytes[] = {
    {&CfgOdo::cog_max_speed_0p1mps, "CFG-ODO-COGMAXSPEED"},
    {&CfgOdo::cog_max_pos_acc_m, "CFG-ODO-COGMAXPOSACC"},
    {&CfgOdo::vel_lp_gain, "CFG-ODO-VELLPGAIN"},
    {&CfgOdo::cog_lp_gain, "CFG-ODO-COGLPGAIN"},
};
}  // namespace

void UbxDevice::poll_cfg_odo(std::uint8_t, Bytes& out) {
  CfgOdo m;
  m.flags = static_cast<std::uint8_t>(bits_of_items(config_, kOdoFlags));
  m.odo_cfg = static_cast<std::uint8_t>(config_.get(item("CFG-ODO-PROFILE")) & 0x7);
  for (const auto& [member, key] : kOdoBytes) m.*member = static_cast<std::uint8_t>(config_.get(item(key)));
  append(m, out);
  ack(kCfgOdo, out);
}

void UbxDevice::handle_cfg_odo(Payload p, std::uint8_t, Bytes& out) {
  CfgOdo m;
  if (!decode(p, m)) return nak(kCfgOdo, out);
  std::vector<CfgKeyValue> v{{item("CFG-ODO-PROFILE"), m.odo_cfg & 0x7u}};
  items_of_bits(m.flags, kOdoFlags, v);
  for (const auto& [member, key] : kOdoBytes) v.push_back({item(key), m.*member});
  config_.set_ram(v) ? ack(kCfgOdo, out) : nak(kCfgOdo, out);
}

// CFG-NMEA (UBX-13003221 "UBX-CFG-NMEA"; on the F9 the CFG-NMEA-* items): filter bits 0..5,
// the version as two hex digits (0x41: 4.1; the item as 41), numSV, flags bits 0..3; the
// 12-byte form adds gnssToFilter (GPS 0, SBAS 1, Galileo 2, QZSS 4, GLONASS 5, BeiDou 6),
// svNumbering, mainTalkerId, gsvTalkerId and version; the 20-byte form bdsTalkerId. A shorter
// set form sets only the fields it has. The poll gives the 20-byte form.
namespace {
constexpr BitItem kNmeaFilter[] = {{0, "CFG-NMEA-OUT_INVFIX"},  {1, "CFG-NMEA-OUT_MSKFIX"},
                                   {2, "CFG-NMEA-OUT_INVTIME"}, {3, "CFG-NMEA-OUT_INVDATE"},
                                   {4, "CFG-NMEA-OUT_ONLYGPS"}, {5, "CFG-NMEA-OUT_FROZENCOG"}};
constexpr BitItem kNmeaFlags[] = {
    {0, "CFG-NMEA-COMPAT"}, {1, "CFG-NMEA-CONSIDER"}, {2, "CFG-NMEA-LIMIT82"}, {3, "CFG-NMEA-HIGHPREC"}};
constexpr BitItem kNmeaGnssFilter[] = {{0, "CFG-NMEA-FILT_GPS"}, {1, "CFG-NMEA-FILT_SBAS"},
                                       {2, "CFG-NMEA-FILT_GAL"}, {4, "CFG-NMEA-FILT_QZSS"},
                                       {5, "CFG-NMEA-FILT_GLO"}, {6, "CFG-NMEA-FILT_BDS"}};
}  // namespace

void UbxDevice::poll_cfg_nmea(std::uint8_t, Bytes& out) {
  const auto get = [&](const char* key) { return static_cast<std::uint8_t>(config_.get(item(key))); };
  CfgNmea m;
  m.filter = static_cast<std::uint8_t>(bits_of_items(config_, kNmeaFilter));
  const std::uint8_t version = get("CFG-NMEA-PROTVER");
  m.nmea_version = static_cast<std::uint8_t>(version / 10 << 4 | version % 10);
  m.num_sv = get("CFG-NMEA-MAXSVS");
  m.flags = static_cast<std::uint8_t>(bits_of_items(config_, kNmeaFlags));
  m.has_v0 = m.has_v1 = true;
  m.gnss_to_filter = bits_of_items(config_, kNmeaGnssFilter);
  m.sv_numbering = get("CFG-NMEA-SVNUMBERING");
  m.main_talker_id = get("CFG-NMEA-MAINTALKERID");
  m.gsv_talker_id = get("CFG-NMEA-GSVTALKERID");
  m.version = 1;
  const auto bds = static_cast<std::uint16_t>(config_.get(item("CFG-NMEA-BDSTALKERID")));
  m.bds_talker_id = {static_cast<std::uint8_t>(bds & 0xFF), static_cast<std::uint8_t>(bds >> 8)};
  append(m, out);
  ack(kCfgNmea, out);
}

void UbxDevice::handle_cfg_nmea(Payload p, std::uint8_t, Bytes& out) {
  CfgNmea m;
  if (!decode(p, m)) return nak(kCfgNmea, out);
  std::vector<CfgKeyValue> v{{item("CFG-NMEA-PROTVER"), (m.nmea_version >> 4) * 10u + (m.nmea_version & 0xFu)},
                             {item("CFG-NMEA-MAXSVS"), m.num_sv}};
  items_of_bits(m.filter, kNmeaFilter, v);
  items_of_bits(m.flags, kNmeaFlags, v);
  if (m.has_v0) {
    items_of_bits(m.gnss_to_filter, kNmeaGnssFilter, v);
    v.insert(v.end(), {{item("CFG-NMEA-SVNUMBERING"), m.sv_numbering},
                       {item("CFG-NMEA-MAINTALKERID"), m.main_talker_id},
                       {item("CFG-NMEA-GSVTALKERID"), m.gsv_talker_id}});
  }
  if (m.has_v1)
    v.push_back({item("CFG-NMEA-BDSTALKERID"), std::uint64_t{m.bds_talker_id[0]} | std::uint64_t{m.bds_talker_id[1]} << 8});
  config_.set_ram(v) ? ack(kCfgNmea, out) : nak(kCfgNmea, out);
}

// CFG-TP5 (UBX-13003221 "UBX-CFG-TP5"; on the F9 the CFG-TP-*_TP1 items, the part having one
// time pulse: tpIdx 1 has no items and is refused). flags: active bit 0, lockGnssFreq 1,
// lockedOtherSet 2, isFreq 3, isLength 4, alignToTow 5, polarity 6, gridUtcGnss bits 7..10.
// isFreq says whether the two frequency/period fields are Hz (the FREQ items) or us (PERIOD);
// isLength whether the two pulse fields are us (LEN) or a duty ratio in 2^-32 (DUTY, an R8 in %).
// The one-byte poll names the time pulse; the empty poll is the first.
namespace {
constexpr BitItem kTp5Flags[] = {{0, "CFG-TP-TP1_ENA"},       {1, "CFG-TP-SYNC_GNSS_TP1"},
                                 {2, "CFG-TP-USE_LOCKED_TP1"}, {3, "CFG-TP-PULSE_DEF"},
                                 {4, "CFG-TP-PULSE_LENGTH_DEF"}, {5, "CFG-TP-ALIGN_TO_TOW_TP1"},
                                 {6, "CFG-TP-POL_TP1"}};
constexpr double kTwoPow32 = 4294967296.0;
}  // namespace

void UbxDevice::handle_cfg_tp5(Payload p, std::uint8_t, Bytes& out) {
  const auto get = [&](const char* key) { return config_.get(item(key)); };
  const auto duty_pct = [&](const char* key) { return std::bit_cast<double>(get(key)); };
  if (p.size() <= 1) {  // a poll
    if (!p.empty() && p[0] != 0) return nak(kCfgTp5, out);
    CfgTp5 m;
    m.flags = bits_of_items(config_, kTp5Flags) | static_cast<std::uint32_t>(get("CFG-TP-TIMEGRID_TP1") & 0xF) << 7;
    const bool is_freq = get("CFG-TP-PULSE_DEF") == 1, is_length = get("CFG-TP-PULSE_LENGTH_DEF") == 1;
    m.ant_cable_delay_ns = static_cast<std::int16_t>(static_cast<std::uint16_t>(get("CFG-TP-ANT_CABLEDELAY")));
    m.freq_period_hz_or_us = static_cast<std::uint32_t>(get(is_freq ? "CFG-TP-FREQ_TP1" : "CFG-TP-PERIOD_TP1"));
    m.freq_period_lock_hz_or_us =
        static_cast<std::uint32_t>(get(is_freq ? "CFG-TP-FREQ_LOCK_TP1" : "CFG-TP-PERIOD_LOCK_TP1"));
    const auto ratio = [&](const char* key) {
      return static_cast<std::uint32_t>(std::clamp(std::round(duty_pct(key) / 100.0 * kTwoPow32), 0.0, kTwoPow32 - 1));
    };
    m.pulse_len_ratio_us_or_2m32 =
        is_length ? static_cast<std::uint32_t>(get("CFG-TP-LEN_TP1")) : ratio("CFG-TP-DUTY_TP1");
    m.pulse_len_ratio_lock_us_or_2m32 =
        is_length ? static_cast<std::uint32_t>(get("CFG-TP-LEN_LOCK_TP1")) : ratio("CFG-TP-DUTY_LOCK_TP1");
    m.user_config_delay_ns = static_cast<std::int32_t>(static_cast<std::uint32_t>(get("CFG-TP-USER_DELAY_TP1")));
    append(m, out);
    return ack(kCfgTp5, out);
  }
  CfgTp5 m;
  if (!decode(p, m) || m.tp_idx != 0) return nak(kCfgTp5, out);
  const bool is_freq = (m.flags & 0x08) != 0, is_length = (m.flags & 0x10) != 0;
  std::vector<CfgKeyValue> v{
      {item("CFG-TP-TIMEGRID_TP1"), m.flags >> 7 & 0xF},
      {item("CFG-TP-ANT_CABLEDELAY"), static_cast<std::uint16_t>(m.ant_cable_delay_ns)},
      {item(is_freq ? "CFG-TP-FREQ_TP1" : "CFG-TP-PERIOD_TP1"), m.freq_period_hz_or_us},
      {item(is_freq ? "CFG-TP-FREQ_LOCK_TP1" : "CFG-TP-PERIOD_LOCK_TP1"), m.freq_period_lock_hz_or_us},
      {item("CFG-TP-USER_DELAY_TP1"), static_cast<std::uint32_t>(m.user_config_delay_ns)}};
  items_of_bits(m.flags, kTp5Flags, v);
  const auto duty_item = [](std::uint32_t ratio_2m32) {
    return std::bit_cast<std::uint64_t>(static_cast<double>(ratio_2m32) / kTwoPow32 * 100.0);
  };
  if (is_length)
    v.insert(v.end(), {{item("CFG-TP-LEN_TP1"), m.pulse_len_ratio_us_or_2m32},
                       {item("CFG-TP-LEN_LOCK_TP1"), m.pulse_len_ratio_lock_us_or_2m32}});
  else
    v.insert(v.end(), {{item("CFG-TP-DUTY_TP1"), duty_item(m.pulse_len_ratio_us_or_2m32)},
                       {item("CFG-TP-DUTY_LOCK_TP1"), duty_item(m.pulse_len_ratio_lock_us_or_2m32)}});
  config_.set_ram(v) ? ack(kCfgTp5, out) : nak(kCfgTp5, out);
}

// CFG-GNSS (M8 32.10.12, F9 5.9.x, deprecated there): every supported system's block. The F9
// reports its CFG-SIGNAL items; the u-blox 8 what was set (or its power-up set).
CfgGnss UbxDevice::current_cfg_gnss() const {
  CfgGnss g;
  if (!protocol27_) {
    decode(legacy_.current(kCfgGnss), g);
    return g;
  }
  g.num_trk_ch_hw = g.num_trk_ch_use = static_cast<std::uint8_t>(std::min(profile_.max_channels, 255));
  for (const F9GnssBlock& f : kF9GnssBlocks) {
    std::uint32_t flags = config_.get(item(f.enable)) ? CfgGnssBlock::kEnable : 0u;
    for (const auto& [bit, key] : f.signals)
      if (key != nullptr && config_.get(item(key))) flags |= static_cast<std::uint32_t>(bit) << CfgGnssBlock::kSigCfgMaskShift;
    g.blocks.push_back({f.gnss_id, f.res_trk_ch, f.max_trk_ch, 0, flags});
  }
  return g;
}

void UbxDevice::poll_cfg_gnss(std::uint8_t, Bytes& out) {
  append(current_cfg_gnss(), out);
  ack(kCfgGnss, out);
}

// A set: its blocks replace those of their systems; the result must be valid (M8 32.10.12
// "Configuration requirements": a major GNSS enabled, at least 4 channels for each enabled
// major GNSS, the reserved channels within those in use; and on the u-blox 8 at most 3 major
// GNSS at once), else ACK-NAK and nothing changes. A valid configuration applies at once.
void UbxDevice::handle_cfg_gnss(Payload p, std::uint8_t, Bytes& out) {
  CfgGnss set;
  if (!decode(p, set)) return nak(kCfgGnss, out);
  CfgGnss g = current_cfg_gnss();
  for (const CfgGnssBlock& b : set.blocks) {
    auto it = std::find_if(g.blocks.begin(), g.blocks.end(), [&](const CfgGnssBlock& x) { return x.gnss_id == b.gnss_id; });
    if (it == g.blocks.end()) return nak(kCfgGnss, out);  // a system the part does not have
    it->flags = b.flags;
    if (!protocol27_) {  // read-only from protocol 23.01 on
      it->res_trk_ch = b.res_trk_ch;
      it->max_trk_ch = b.max_trk_ch;
    }
  }
  int majors = 0, reserved = 0;
  for (const CfgGnssBlock& b : g.blocks) {
    reserved += b.res_trk_ch;
    if (!major_gnss(b.gnss_id) || !(b.flags & CfgGnssBlock::kEnable)) continue;
    ++majors;
    if (b.max_trk_ch < 4 || !(b.flags >> CfgGnssBlock::kSigCfgMaskShift & 0xFF)) return nak(kCfgGnss, out);
  }
  if (majors == 0 || (!protocol27_ && majors > 3) || reserved > g.num_trk_ch_use) return nak(kCfgGnss, out);
  if (!protocol27_) {
    Bytes frame, unused;
    append(g, frame);  // the whole frame: the payload lies between the 6-byte header and the checksum
    if (!legacy_.handle(kCfgGnss, std::span<const std::uint8_t>(frame).subspan(6, frame.size() - 8), unused))
      return nak(kCfgGnss, out);
    stale_ = true;
    return ack(kCfgGnss, out);
  }
  std::vector<CfgKeyValue> v;
  for (const F9GnssBlock& f : kF9GnssBlocks) {
    const auto it = std::find_if(g.blocks.begin(), g.blocks.end(), [&](const CfgGnssBlock& x) { return x.gnss_id == f.gnss_id; });
    v.push_back({item(f.enable), (it->flags & CfgGnssBlock::kEnable) ? 1u : 0u});
    for (const auto& [bit, key] : f.signals)
      if (key != nullptr) v.push_back({item(key), (it->flags >> CfgGnssBlock::kSigCfgMaskShift & bit) ? 1u : 0u});
  }
  config_.set_ram(v) ? ack(kCfgGnss, out) : nak(kCfgGnss, out);
}

// CFG-CFG: clear, save, load (in that order) on BBR and flash, or on the layers of deviceMask
// (bit 0 BBR, bit 1 flash).
void UbxDevice::handle_cfg_cfg(Payload p, std::uint8_t, Bytes& out) {
  CfgCfg c;
  if (!decode(p, c)) return nak(kCfgCfg, out);
  const std::uint8_t layers = c.has_device_mask ? static_cast<std::uint8_t>(c.device_mask & 0x03) : 0x03;
  if (c.clear_mask) {
    config_.clear(layers);
    legacy_.clear();
  }
  if (c.save_mask) {
    config_.save(layers);
    legacy_.save();
  }
  if (c.load_mask) {
    config_.load();
    legacy_.load();
    stale_ = true;
  }
  ack(kCfgCfg, out);
}

void UbxDevice::handle_cfg_rst(Payload p, std::uint8_t, Bytes& out) {
  // Not acknowledged (interface description, CFG-RST). The processor resets in modes 0x00, 0x01
  // and 0x04; navBbrMask 0x0000 is a hot start, 0x0001 a warm start, anything else (0xFFFF a
  // cold start) as long as a cold one.
  CfgRst r;
  if (!decode(p, r)) return nak(kCfgRst, out);
  if (r.nav_bbr_mask == CfgRst::kColdStart) status_.odo_distance_m = status_.odo_total_m = 0.0;
  const RestartKind kind = r.nav_bbr_mask == CfgRst::kHotStart    ? RestartKind::kHot
                           : r.nav_bbr_mask == CfgRst::kWarmStart ? RestartKind::kWarm
                                                                  : RestartKind::kCold;
  restart(kind,
          r.reset_mode == CfgRst::kHardwareReset || r.reset_mode == CfgRst::kControlledSoftwareReset ||
              r.reset_mode == CfgRst::kHardwareResetAfterShutdown,
          last_fix_.t);
}

// A processor reset rebuilds the RAM layer from the layers below (UBX-18010854 6.6) and restores
// a backup in flash (UPD-SOS); a survey-in starts again with the navigation.
void UbxDevice::restart(RestartKind kind, bool hardware, GpsTime t) {
  if (hardware) {
    sos_restored_ = sos_backup_;
    config_.reload();
    legacy_.load();
  }
  survey_settings_.reset();
  stale_ = true;
  GnssDevice::restart(kind, hardware, t);
}

void UbxDevice::handle_valset(Payload p, std::uint8_t, Bytes& out) {
  CfgValset v;
  decode(p, v) && config_.valset(v) ? ack(kCfgValset, out) : nak(kCfgValset, out);
}

void UbxDevice::handle_valdel(Payload p, std::uint8_t, Bytes& out) {
  CfgValdel v;
  decode(p, v) && config_.valdel(v) ? ack(kCfgValdel, out) : nak(kCfgValdel, out);
}

void UbxDevice::handle_valget(Payload p, std::uint8_t, Bytes& out) {
  CfgValgetRequest req;
  std::optional<CfgValgetResponse> r;
  if (!decode(p, req) || !(r = config_.valget(req))) return nak(kCfgValget, out);
  ++counters_.polls;
  append(*r, out);
  ack(kCfgValget, out);
}

// ---- Output --------------------------------------------------------------------------------

bool UbxDevice::output_message(MsgId id, Bytes& out) {
  const std::span<const UbxOutput> outs = ubx_outputs();
  for (std::size_t i = 0; i < outs.size(); ++i)
    if (outs[i].id == id && (protocol27_ ? outs[i].f9 : outs[i].m8)) {
      emit_ubx_outputs(std::uint64_t{1} << i, last_fix_, last_meas_, nav_, mode_, status_, lists_, out);
      return true;
    }
  return false;
}

void UbxDevice::take_epoch(const ReceiverFix& fix, const EpochMeasurements& meas, std::int64_t epoch_index) {
  last_fix_ = fix;
  last_meas_ = meas;
  epoch_index_ = epoch_index;
  if (last_fix_.fix == FixType::k3D)
    survey_.add(last_fix_.t, last_fix_.p_ecef_m, std::hypot(last_fix_.sigma_h_m, last_fix_.sigma_v_m));
  status_.svin = survey_.state();
  hold_time_mode_position(last_fix_);
  count_distance(last_fix_);
  // A fix outside the output filters is no fix to NMEA: status V, quality 0, navMode 1 and
  // empty fields (F9 interface description 4.1.6 "Position Fix Flags", "GNSS fix, but user
  // limits exceeded"; 4.1.8).
  fix_filtered_out_ = last_fix_.fix != FixType::kNone && !within_output_filters(last_fix_, mode_, status_);
  if (fix_filtered_out_) {
    nmea_fix_ = last_fix_;
    nmea_fix_.fix = FixType::kNone;
  }
}

// Time mode (ZED-F9P integration manual UBX-18010802 "Base station", ZED-F9T integration manual
// "Timing receiver position": "the position of the receiver is known and fixed and only the
// time and frequency is calculated"): once the survey-in has finished, or with a fixed
// position, a receiver that solves reports the time-only fix (NAV-PVT fixType 5) at that
// position, standing still, as accurate as the survey's mean or the configured accuracy. NMEA
// has no row for it (F9 interface description 4.1.6); its sentences carry that position as a
// fix.
void UbxDevice::hold_time_mode_position(ReceiverFix& fix) {
  status_.time_only = false;
  if (fix.fix == FixType::kNone) return;
  const SurveyInState& svin = status_.svin;
  std::optional<FixedPosition> base = fixed_position_;
  if (svin.valid) base = FixedPosition{svin.mean_ecef_m, svin.mean_acc_m};
  if (!base) return;
  status_.time_only = true;
  fix.p_ecef_m = base->p_ecef_m;
  fix.position = geodetic_from_ecef(base->p_ecef_m);
  if (fix.v_ned_mps) fix.v_ned_mps = Vec3::Zero();
  // The 3D accuracy shared out: equal horizontal and vertical parts, equal north and east.
  fix.sigma_h_m = fix.sigma_v_m = base->acc_m / std::sqrt(2.0);
  fix.sigma_n_m = fix.sigma_e_m = fix.sigma_h_m / std::sqrt(2.0);
}

// The odometer (CFG-ODO-USE_ODO; UBX-13003221 "Odometer"): the ground speed integrated over
// the time between fixes. Speeds below kStill_mps count as standing still, so that a parked
// receiver's velocity noise (a few cm/s) adds no distance.
void UbxDevice::count_distance(const ReceiverFix& fix) {
  constexpr double kStill_mps = 0.2;
  if (!status_.odometer || fix.fix == FixType::kNone || !fix.v_ned_mps) {
    odo_last_t_.reset();
    return;
  }
  const double speed_mps = std::hypot(fix.v_ned_mps->x(), fix.v_ned_mps->y());
  if (odo_last_t_ && speed_mps >= kStill_mps) {
    const double d_m = speed_mps * std::max(seconds_between(fix.t, *odo_last_t_), 0.0);
    status_.odo_distance_m += d_m;
    status_.odo_total_m += d_m;
  }
  odo_last_t_ = fix.t;
}

void UbxDevice::encode(ReceiverPort port, std::string& out) {
  const PortSettings& s = ports_[static_cast<std::size_t>(port)];
  const std::size_t before = out.size();
  if (s.out_ubx) {
    std::uint64_t due = 0;
    const std::span<const UbxOutput> outs = ubx_outputs();
    for (std::size_t i = 0; i < outs.size(); ++i) {
      const int r = s.ubx_rates[i];
      if (r > 0 && epoch_index_ % r == 0 && (protocol27_ ? outs[i].f9 : outs[i].m8)) due |= std::uint64_t{1} << i;
    }
    scratch_.clear();
    emit_ubx_outputs(due, last_fix_, last_meas_, nav_, mode_, status_, lists_, scratch_);
    out.append(reinterpret_cast<const char*>(scratch_.data()), scratch_.size());
  }
  if (s.out_nmea) s.nmea->encode(fix_filtered_out_ ? nmea_fix_ : last_fix_, epoch_index_, out);
  status_.ports[static_cast<std::size_t>(port)].tx_bytes += static_cast<std::uint32_t>(out.size() - before);
}

// ---- The device of a profile ----------------------------------------------------------------

namespace {
// A receiver that only talks NMEA: every port gets the same sentences.
class NmeaDevice final : public GnssDevice {
 public:
  NmeaDevice(const GnssProfile& p, ReceiverMode mode) : out_(p, mode), period_ns_(std::llround(1e9 / p.rate_hz)) {}
  const ReceiverFix& reported_fix() const override { return *fix_; }
  void encode(ReceiverPort, std::string& out) override { out_.encode(*fix_, epoch_index_, out); }
  std::int64_t period_ns() const override { return period_ns_; }

 private:
  void take_epoch(const ReceiverFix& fix, const EpochMeasurements&, std::int64_t epoch_index) override {
    fix_ = &fix;
    epoch_index_ = epoch_index;
  }

  NmeaOutput out_;
  std::int64_t period_ns_;
  const ReceiverFix* fix_ = &none_;  // the caller's, between update() and encode()
  ReceiverFix none_;                 // before the first update
  std::int64_t epoch_index_ = 0;
};
}  // namespace

std::unique_ptr<GnssDevice> make_gnss_device(const GnssProfile& profile, ReceiverMode mode, const NavData& nav) {
  if (profile.ubx) return std::make_unique<UbxDevice>(profile, mode, nav);
  return std::make_unique<NmeaDevice>(profile, mode);
}

}  // namespace navemu
