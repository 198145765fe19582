#include "emulator/ubx_device.hpp"

#include <algorithm>
#include <cmath>

#include "models/geodesy.hpp"
#include "protocols/gps_lnav.hpp"
#include "models/prn_table.hpp"
#include "models/reuse.hpp"

namespace navemu {

namespace {

using namespace ubx;

constexpr std::uint16_t key(MsgId id) { return static_cast<std::uint16_t>(id.cls << 8 | id.id); }

// Every UBX output message the device can produce, in the order of one epoch's output: raw
// measurement data first (it is measured before the solution), the navigation messages, and
// NAV-EOE closing the epoch (u-blox interface description, "NAV-EOE").
struct OutputMessage {
  const char* name;
  MsgId id;
  std::uint32_t valset_uart1;  // CFG-MSGOUT-..._UART1 and _USB keys (protocol 27+; 0: none)
  std::uint32_t valset_usb;
};
constexpr OutputMessage kOutputs[] = {
    {"RXM-RAWX", kRxmRawx, cfgkey::kMsgoutUbxRxmRawxUart1, cfgkey::kMsgoutUbxRxmRawxUsb},
    {"RXM-SFRBX", kRxmSfrbx, cfgkey::kMsgoutUbxRxmSfrbxUart1, cfgkey::kMsgoutUbxRxmSfrbxUsb},
    {"NAV-POSECEF", kNavPosecef, cfgkey::kMsgoutUbxNavPosecefUart1, cfgkey::kMsgoutUbxNavPosecefUsb},
    {"NAV-POSLLH", kNavPosllh, cfgkey::kMsgoutUbxNavPosllhUart1, cfgkey::kMsgoutUbxNavPosllhUsb},
    {"NAV-STATUS", kNavStatus, cfgkey::kMsgoutUbxNavStatusUart1, cfgkey::kMsgoutUbxNavStatusUsb},
    {"NAV-DOP", kNavDop, cfgkey::kMsgoutUbxNavDopUart1, cfgkey::kMsgoutUbxNavDopUsb},
    {"NAV-SOL", kNavSol, 0, 0},
    {"NAV-PVT", kNavPvt, cfgkey::kMsgoutUbxNavPvtUart1, cfgkey::kMsgoutUbxNavPvtUsb},
    {"NAV-VELECEF", kNavVelecef, cfgkey::kMsgoutUbxNavVelecefUart1, cfgkey::kMsgoutUbxNavVelecefUsb},
    {"NAV-VELNED", kNavVelned, cfgkey::kMsgoutUbxNavVelnedUart1, cfgkey::kMsgoutUbxNavVelnedUsb},
    {"NAV-TIMEGPS", kNavTimegps, cfgkey::kMsgoutUbxNavTimegpsUart1, cfgkey::kMsgoutUbxNavTimegpsUsb},
    {"NAV-TIMEUTC", kNavTimeutc, cfgkey::kMsgoutUbxNavTimeutcUart1, cfgkey::kMsgoutUbxNavTimeutcUsb},
    {"NAV-CLOCK", kNavClock, cfgkey::kMsgoutUbxNavClockUart1, cfgkey::kMsgoutUbxNavClockUsb},
    {"NAV-SVINFO", kNavSvinfo, 0, 0},
    {"NAV-SAT", kNavSat, cfgkey::kMsgoutUbxNavSatUart1, cfgkey::kMsgoutUbxNavSatUsb},
    {"NAV-EOE", kNavEoe, cfgkey::kMsgoutUbxNavEoeUart1, cfgkey::kMsgoutUbxNavEoeUsb},
};

// The message and port a CFG-MSGOUT key configures, if it is one.
std::optional<std::pair<MsgId, std::uint8_t>> msgout_key(std::uint32_t k) {
  for (const OutputMessage& m : kOutputs) {
    if (m.valset_uart1 && k == m.valset_uart1) return std::pair{m.id, kPortUart1};
    if (m.valset_usb && k == m.valset_usb) return std::pair{m.id, kPortUsb};
  }
  return std::nullopt;
}

// NMEA sentences in CFG-MSG (class 0xF0) by their message ID.
constexpr std::pair<std::uint8_t, const char*> kNmeaIds[] = {
    {0x00, "GGA"}, {0x01, "GLL"}, {0x02, "GSA"}, {0x03, "GSV"},
    {0x04, "RMC"}, {0x05, "VTG"}, {0x07, "GST"}, {0x08, "ZDA"}};

constexpr double kMaxLockTime_ms = 64500.0;  // RXM-RAWX locktime saturates here

template <typename T>
T clamp_cast(double v) {
  const double lo = static_cast<double>(std::numeric_limits<T>::lowest());
  const double hi = static_cast<double>(std::numeric_limits<T>::max());
  return static_cast<T>(std::clamp(std::round(v), lo, hi));
}

std::uint8_t fix_type(FixType f) {
  switch (f) {
    case FixType::kNone: return kFixNone;
    case FixType::kDeadReckoning: return kFixDeadReckoning;
    case FixType::k2D: return kFix2d;
    case FixType::k3D: return kFix3d;
  }
  return kFixNone;
}

// Accuracy estimates of the receiver (1-sigma), wire units.
struct Accuracy {
  double h_m, v_m, p_m, s_mps;
};
Accuracy accuracy(const ReceiverFix& fix) {
  if (fix.fix == FixType::kNone) return {9999.0, 9999.0, 9999.0, 20.0};
  const double p = std::hypot(fix.sigma_h_m, fix.sigma_v_m);
  // Doppler velocity: about 5 cm/s of range-rate noise times the PDOP.
  return {fix.sigma_h_m, fix.sigma_v_m, p, 0.05 * std::max(fix.dops.pdop, 1.0)};
}

// The GPS broadcast record of a satellite as IS-GPS-200 subframes 1-3 carry it.
lnav::LnavEphemeris to_lnav(const GpsEphemeris& e) {
  lnav::LnavEphemeris l;
  l.prn = e.prn;
  l.week = to_week_tow(e.toe).week;
  l.codes_on_l2 = e.codes_on_l2 ? e.codes_on_l2 : 1;
  l.ura_index = lnav::lnav_ura_index(e.ura_m);
  l.health = e.health;
  // IODE must equal the 8 LSBs of IODC (IS-GPS-200 20.3.4.4).
  l.iodc = (e.iodc & ~0xFF) | (e.iode & 0xFF);
  l.iode = e.iode & 0xFF;
  l.l2p_data_flag = e.l2p_data_flag;
  l.tgd_s = e.tgd_s;
  l.toc_s = to_week_tow(e.toc).tow_s;
  l.af0_s = e.af0_s;
  l.af1_sps = e.af1_sps;
  l.af2_sps2 = e.af2_sps2;
  l.crs_m = e.crs_m;
  l.delta_n_radps = e.delta_n_radps;
  l.m0_rad = e.m0_rad;
  l.cuc_rad = e.cuc_rad;
  l.e = e.e;
  l.cus_rad = e.cus_rad;
  l.sqrt_a_sqrtm = e.sqrt_a_sqrtm;
  l.toe_s = to_week_tow(e.toe).tow_s;
  l.fit_interval_flag = e.fit_interval_h > 4.0 ? 1 : 0;
  l.cic_rad = e.cic_rad;
  l.omega0_rad = e.omega0_rad;
  l.cis_rad = e.cis_rad;
  l.i0_rad = e.i0_rad;
  l.crc_m = e.crc_m;
  l.omega_rad = e.omega_rad;
  l.omega_dot_radps = e.omega_dot_radps;
  l.idot_radps = e.idot_radps;
  return l;
}

}  // namespace

UbxDevice::UbxDevice(const GnssProfile& profile, ReceiverMode mode, const NavData& nav)
    : profile_(profile), mode_(mode), nav_(nav) {
  // Room for every PRN: copying and refilling the epoch's lists never allocates.
  last_fix_.satellites.reserve(kMaxPrn);
  last_meas_.sats.reserve(kMaxPrn);
  scratch_svinfo_.channels.reserve(kMaxPrn);
  scratch_sat_.svs.reserve(kMaxPrn);
  scratch_rawx_.meas.reserve(kMaxPrn);
  const UbxSettings& u = *profile_.ubx;
  baud_ = profile_.baud;
  out_proto_ = static_cast<std::uint16_t>(kProtoUbx | (u.nmea_out ? kProtoNmea : 0));
  meas_rate_ms_ = static_cast<std::uint16_t>(std::lround(1000.0 / profile_.rate_hz));
  for (const auto& [name, rate] : u.messages)
    for (const OutputMessage& m : kOutputs)
      if (name == m.name) set_rate(m.id, port_id_, rate);
  for (const auto& [name, rate] : profile_.sentences)
    for (const auto& [id, n] : kNmeaIds)
      if (name == n) set_rate({kClassNmea, id}, port_id_, rate);
  nav5_.dyn_model = CfgNav5::kDynPortable;
  nav5_.fix_mode = 3;
  nav5_.min_elev_deg = static_cast<std::int8_t>(std::lround(profile_.elevation_mask_deg));
  gnss_.msg_ver = 0;
  gnss_.num_trk_ch_hw = static_cast<std::uint8_t>(std::min(profile_.max_channels, 255));
  gnss_.num_trk_ch_use = gnss_.num_trk_ch_hw;
  gnss_.blocks.push_back({0, 8, 16, 0, CfgGnssBlock::kEnable | (1u << 16)});  // GPS L1C/A
  rebuild_nmea();
  scratch_.reserve(8192);
}

void UbxDevice::rebuild_nmea() {
  GnssProfile p = profile_;
  p.sentences.clear();
  // Keep the profile's order of sentences, then any other one a client switched on.
  for (const auto& [id, n] : kNmeaIds) {
    if (const int r = rate({kClassNmea, id}); r > 0) p.sentences.emplace_back(n, r);
  }
  std::stable_sort(p.sentences.begin(), p.sentences.end(), [&](const auto& a, const auto& b) {
    const auto rank = [&](const std::string& s) {
      for (std::size_t i = 0; i < profile_.sentences.size(); ++i)
        if (profile_.sentences[i].first == s) return i;
      return profile_.sentences.size();
    };
    return rank(a.first) < rank(b.first);
  });
  nmea_ = std::make_unique<NmeaOutput>(p, mode_);
}

std::int64_t UbxDevice::period_ns() const {
  return static_cast<std::int64_t>(meas_rate_ms_) * nav_rate_ * 1'000'000;
}

std::optional<int> UbxDevice::take_baud_change() {
  std::optional<int> b = pending_baud_;
  pending_baud_.reset();
  return b;
}

int UbxDevice::rate(MsgId id, std::uint8_t port) const {
  const auto it = rates_.find(key(id));
  return it == rates_.end() || port >= kNumPorts ? 0 : it->second[port];
}

void UbxDevice::set_rate(MsgId id, std::uint8_t port, int r) {
  if (port < kNumPorts) rates_[key(id)][port] = static_cast<std::uint8_t>(std::clamp(r, 0, 255));
}

UbxDeviceCounters UbxDevice::counters() const {
  UbxDeviceCounters c = counters_;
  c.checksum_errors = parser_.counters().checksum_errors;
  c.too_long = parser_.counters().too_long;
  c.junk_bytes = parser_.counters().junk_bytes;
  return c;
}

// ---- Input: configuration and polls ------------------------------------------------------

void UbxDevice::receive(std::span<const std::uint8_t> bytes, std::string& replies) {
  scratch_.clear();
  parser_.feed(bytes, [&](Parser::Result r) {
    if (r != Parser::Result::kFrame) return;
    ++counters_.frames;
    if (in_proto_ & kProtoUbx) handle(parser_.cls(), parser_.id(), parser_.payload(), scratch_);
  });
  replies.append(reinterpret_cast<const char*>(scratch_.data()), scratch_.size());
}

void UbxDevice::handle(std::uint8_t cls, std::uint8_t id, std::span<const std::uint8_t> p,
                       std::vector<std::uint8_t>& out) {
  const auto ack = [&] {
    ++counters_.acks;
    append(AckAck{cls, id}, out);
  };
  const auto nak = [&] {
    ++counters_.naks;
    append(AckNak{cls, id}, out);
  };
  const MsgId msg{cls, id};

  if (msg == kMonVer && p.empty()) {
    ++counters_.polls;
    const UbxSettings& u = *profile_.ubx;
    append(MonVer{u.sw_version, u.hw_version, u.extensions}, out);
    return;
  }
  if (msg == kMonHw && p.empty()) {
    ++counters_.polls;
    MonHw hw;
    hw.a_status = MonHw::kAntOk;
    hw.a_power = 1;
    hw.noise_per_ms = 85;
    hw.agc_cnt = 5000;
    append(hw, out);
    return;
  }
  if (cls != kClassCfg) {
    // A poll of an output message is answered with the latest epoch's message.
    if (p.empty() && output_message(msg, out)) ++counters_.polls;
    return;
  }

  if (msg == kCfgPrt) {
    CfgPrtPoll poll;
    CfgPrt set;
    if (decode(p, poll)) {
      ++counters_.polls;
      CfgPrt r;
      r.port_id = poll.has_port_id ? poll.port_id : port_id_;
      r.mode = CfgPrt::kMode8N1;
      r.baud_rate = static_cast<std::uint32_t>(baud_);
      r.in_proto_mask = in_proto_;
      r.out_proto_mask = out_proto_;
      append(r, out);
      ack();
    } else if (decode(p, set)) {
      if (set.port_id != port_id_ && set.port_id != kPortUsb) return nak();
      in_proto_ = set.in_proto_mask;
      out_proto_ = set.out_proto_mask;
      if (set.baud_rate != 0 && static_cast<int>(set.baud_rate) != baud_) {
        baud_ = static_cast<int>(set.baud_rate);
        pending_baud_ = baud_;  // after the acknowledgement, as on the hardware
      }
      ack();
    } else {
      nak();
    }
    return;
  }
  if (msg == kCfgMsg) {
    CfgMsgPoll poll;
    CfgMsgCurrentPort cur;
    CfgMsg all;
    if (decode(p, poll)) {
      ++counters_.polls;
      CfgMsg r;
      r.msg_class = poll.msg_class;
      r.msg_id = poll.msg_id;
      for (std::uint8_t port = 0; port < kNumPorts; ++port)
        r.rate[port] = static_cast<std::uint8_t>(rate({poll.msg_class, poll.msg_id}, port));
      append(r, out);
      ack();
      return;
    }
    // The 3-byte form sets the rate on the port the command came in on, the 8-byte form on all.
    std::optional<MsgId> change;
    if (decode(p, cur)) change = MsgId{cur.msg_class, cur.msg_id};
    else if (decode(p, all)) change = MsgId{all.msg_class, all.msg_id};
    if (!change) return nak();
    const MsgId target = *change;
    // The receiver takes a rate for any message of its output classes (gpsd also sets e.g.
    // NAV-TIMELS and NMEA GBS); it sends those it produces. Other classes are refused.
    constexpr std::uint8_t kOutputClasses[] = {kClassNav, kClassRxm, kClassInf, kClassMon,
                                               kClassTim, kClassEsf, kClassHnr, kClassSec,
                                               kClassNmea, kClassPubx};
    if (std::find(std::begin(kOutputClasses), std::end(kOutputClasses), target.cls) ==
        std::end(kOutputClasses))
      return nak();
    if (p.size() == CfgMsgCurrentPort::kPayloadSize)
      set_rate(target, port_id_, cur.rate);
    else
      for (std::uint8_t port = 0; port < kNumPorts; ++port) set_rate(target, port, all.rate[port]);
    if (target.cls == kClassNmea) rebuild_nmea();
    return ack();
  }
  if (msg == kCfgRate) {
    CfgRate r;
    if (p.empty()) {
      ++counters_.polls;
      append(CfgRate{meas_rate_ms_, nav_rate_, time_ref_}, out);
      return ack();
    }
    // Measurement rate 25 Hz at most (40 ms), navigation rate at least one measurement.
    if (!decode(p, r) || r.meas_rate_ms < 40 || r.nav_rate_cycles < 1 || r.nav_rate_cycles > 127 ||
        r.time_ref > CfgRate::kTimeRefGalileo)
      return nak();
    meas_rate_ms_ = r.meas_rate_ms;
    nav_rate_ = r.nav_rate_cycles;
    time_ref_ = r.time_ref;
    return ack();
  }
  if (msg == kCfgNav5) {
    CfgNav5 n;
    if (p.empty()) {
      ++counters_.polls;
      append(nav5_, out);
      return ack();
    }
    if (!decode(p, n)) return nak();
    if (n.mask & CfgNav5::kMaskDyn) nav5_.dyn_model = n.dyn_model;
    if (n.mask & CfgNav5::kMaskMinEl) nav5_.min_elev_deg = n.min_elev_deg;
    if (n.mask & CfgNav5::kMaskPosFixMode) nav5_.fix_mode = n.fix_mode;
    return ack();
  }
  if (msg == kCfgGnss) {
    CfgGnss g;
    if (p.empty()) {
      ++counters_.polls;
      append(gnss_, out);
      return ack();
    }
    return decode(p, g) ? ack() : nak();
  }
  if (msg == kCfgCfg) {
    CfgCfg c;
    return decode(p, c) ? ack() : nak();
  }
  if (msg == kCfgRst) {
    // Not acknowledged (interface description, CFG-RST). The fix returns after the part's
    // time to first fix (u-blox M8 data sheet: hot start 1 s, cold start 26 s; a warm start
    // still has to collect the ephemerides, about as long).
    CfgRst r;
    if (!decode(p, r)) return nak();
    const double outage_s = r.nav_bbr_mask == CfgRst::kHotStart    ? 1.0
                            : r.nav_bbr_mask == CfgRst::kWarmStart ? 25.0
                                                                   : 26.0;
    restart_until_ = last_fix_.t.plus_s(outage_s);
    return;
  }
  const bool protocol27 = profile_.ubx->protver >= "27";
  if (msg == kCfgValset && protocol27) return handle_valset(p, out);
  if (msg == kCfgValget && protocol27) return handle_valget(p, out);
  if (msg == kCfgValdel && protocol27) {
    // Deleting from the battery-backed or flash layers leaves the running (RAM) configuration
    // as it is; nothing is stored beyond it here.
    CfgValdel d;
    return decode(p, d) ? ack() : nak();
  }
  nak();  // a configuration message this receiver does not know
}

void UbxDevice::handle_valset(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out) {
  CfgValset v;
  const auto nak = [&] {
    ++counters_.naks;
    append(AckNak{kCfgValset.cls, kCfgValset.id}, out);
  };
  if (!decode(p, v)) return nak();
  // All or nothing: every key must be known and its value valid before any is applied.
  for (const CfgKeyValue& kv : v.values) {
    bool known = kv.key_id == cfgkey::kRateMeas || kv.key_id == cfgkey::kRateNav ||
                 kv.key_id == cfgkey::kRateTimeref || kv.key_id == cfgkey::kUart1Baudrate ||
                 kv.key_id == cfgkey::kUart1outprotNmea || kv.key_id == cfgkey::kUart1outprotUbx ||
                 kv.key_id == cfgkey::kUart1inprotNmea || kv.key_id == cfgkey::kUart1inprotUbx ||
                 kv.key_id == cfgkey::kNavspgDynmodel;
    known = known || msgout_key(kv.key_id).has_value() || kv.key_id == cfgkey::kUsbinprotUbx ||
            kv.key_id == cfgkey::kUsbinprotNmea || kv.key_id == cfgkey::kUsboutprotUbx ||
            kv.key_id == cfgkey::kUsboutprotNmea;
    if (!known) return nak();
    if (kv.key_id == cfgkey::kRateMeas && kv.value < 40) return nak();  // 25 Hz at most, as CFG-RATE
    if (kv.key_id == cfgkey::kRateNav && (kv.value < 1 || kv.value > 127)) return nak();
  }
  for (const CfgKeyValue& kv : v.values) {
    const auto flag = [&](std::uint16_t& mask, std::uint16_t bit) {
      mask = static_cast<std::uint16_t>(kv.value ? (mask | bit) : (mask & ~bit));
    };
    if (kv.key_id == cfgkey::kRateMeas) meas_rate_ms_ = static_cast<std::uint16_t>(kv.value);
    if (kv.key_id == cfgkey::kRateNav) nav_rate_ = static_cast<std::uint16_t>(kv.value);
    if (kv.key_id == cfgkey::kRateTimeref) time_ref_ = static_cast<std::uint16_t>(kv.value);
    if (kv.key_id == cfgkey::kNavspgDynmodel) nav5_.dyn_model = static_cast<std::uint8_t>(kv.value);
    if (kv.key_id == cfgkey::kUart1outprotNmea) flag(out_proto_, kProtoNmea);
    if (kv.key_id == cfgkey::kUart1outprotUbx) flag(out_proto_, kProtoUbx);
    if (kv.key_id == cfgkey::kUart1inprotNmea) flag(in_proto_, kProtoNmea);
    if (kv.key_id == cfgkey::kUart1inprotUbx) flag(in_proto_, kProtoUbx);
    if (kv.key_id == cfgkey::kUart1Baudrate && static_cast<int>(kv.value) != baud_) {
      baud_ = static_cast<int>(kv.value);
      pending_baud_ = baud_;
    }
    if (const auto mk = msgout_key(kv.key_id)) set_rate(mk->first, mk->second, static_cast<int>(kv.value));
    // The USB port is not emulated: its protocol masks are kept for VALGET only.
    if ((kv.key_id >> 16) == 0x1077 || (kv.key_id >> 16) == 0x1078) usb_proto_keys_[kv.key_id] = kv.value;
  }
  ++counters_.acks;
  append(AckAck{kCfgValset.cls, kCfgValset.id}, out);
}

std::optional<std::uint64_t> UbxDevice::value_of(std::uint32_t k) const {
  if (k == cfgkey::kRateMeas) return meas_rate_ms_;
  if (k == cfgkey::kRateNav) return nav_rate_;
  if (k == cfgkey::kRateTimeref) return time_ref_;
  if (k == cfgkey::kNavspgDynmodel) return nav5_.dyn_model;
  if (k == cfgkey::kUart1Baudrate) return static_cast<std::uint64_t>(baud_);
  if (k == cfgkey::kUart1outprotNmea) return (out_proto_ & kProtoNmea) ? 1 : 0;
  if (k == cfgkey::kUart1outprotUbx) return (out_proto_ & kProtoUbx) ? 1 : 0;
  if (k == cfgkey::kUart1inprotNmea) return (in_proto_ & kProtoNmea) ? 1 : 0;
  if (k == cfgkey::kUart1inprotUbx) return (in_proto_ & kProtoUbx) ? 1 : 0;
  if (const auto mk = msgout_key(k)) return static_cast<std::uint64_t>(rate(mk->first, mk->second));
  if ((k >> 16) == 0x1077 || (k >> 16) == 0x1078) {
    const auto it = usb_proto_keys_.find(k);
    return it != usb_proto_keys_.end() ? it->second : 1;  // USB takes UBX and NMEA by default
  }
  return std::nullopt;
}

void UbxDevice::handle_valget(std::span<const std::uint8_t> p, std::vector<std::uint8_t>& out) {
  CfgValgetRequest req;
  const auto nak = [&] {
    ++counters_.naks;
    append(AckNak{kCfgValget.cls, kCfgValget.id}, out);
  };
  if (!decode(p, req)) return nak();
  // The default layer answers the power-up configuration; RAM, BBR and flash the running one
  // (nothing here is saved apart from it).
  std::unique_ptr<UbxDevice> defaults;
  if (req.layer == kLayerDefault) defaults = std::make_unique<UbxDevice>(profile_, mode_, nav_);
  const UbxDevice& from = defaults ? *defaults : *this;
  CfgValgetResponse r;
  r.layer = req.layer;
  r.position = req.position;
  for (std::uint32_t k : req.keys) {
    const std::optional<std::uint64_t> v = from.value_of(k);
    if (!v) return nak();
    r.values.push_back({k, *v});
  }
  ++counters_.polls;
  append(r, out);
  ++counters_.acks;
  append(AckAck{kCfgValget.cls, kCfgValget.id}, out);
}

// ---- Output --------------------------------------------------------------------------------

bool UbxDevice::output_message(MsgId id, std::vector<std::uint8_t>& out) const {
  const ReceiverFix& fix = last_fix_;
  const EpochMeasurements& meas = last_meas_;
  const WeekTow wt = to_week_tow(fix.t);
  const auto i_tow = static_cast<std::uint32_t>(std::llround(wt.tow_s * 1000.0)) % 604'800'000u;
  const bool valid = fix.fix != FixType::kNone;
  const Accuracy acc = accuracy(fix);
  const Vec3 v_ned = fix.v_ned_mps.value_or(Vec3::Zero());
  const Vec3 v_ecef = valid ? Vec3(R_ned_from_ecef(fix.position).transpose() * v_ned) : Vec3::Zero();
  const double g_speed = std::hypot(v_ned.x(), v_ned.y());
  double heading_deg = std::atan2(v_ned.y(), v_ned.x()) * kRadToDeg;
  if (heading_deg < 0.0) heading_deg += 360.0;
  const double separation_m = fix.geoid_separation_m;  // 0 without a fix
  const std::uint8_t status_flags =
      static_cast<std::uint8_t>((valid ? NavStatus::kGpsFixOk : 0) |
                                (mode_ == ReceiverMode::kDgps ? NavStatus::kDiffSoln : 0) |
                                NavStatus::kWknSet | NavStatus::kTowSet);
  const int leap_s = leap_seconds_at_gps(fix.t, nav_.leap_seconds);
  const auto used = [&](int prn) {
    for (const ReceiverSatellite& s : fix.satellites)
      if (s.prn == prn) return s.used;
    return false;
  };

  if (id == kNavPvt) {
    const CalendarTime c = utc_from_gps(fix.t);
    const double whole = std::floor(c.second);
    NavPvt m;
    m.i_tow_ms = i_tow;
    m.year = static_cast<std::uint16_t>(c.year);
    m.month = static_cast<std::uint8_t>(c.month);
    m.day = static_cast<std::uint8_t>(c.day);
    m.hour = static_cast<std::uint8_t>(c.hour);
    m.min = static_cast<std::uint8_t>(c.minute);
    m.sec = static_cast<std::uint8_t>(whole);
    m.nano_ns = static_cast<std::int32_t>(std::lround((c.second - whole) * 1e9));
    m.valid = NavPvt::kValidDate | NavPvt::kValidTime | NavPvt::kFullyResolved;
    m.t_acc_ns = 20;
    m.fix_type = fix_type(fix.fix);
    m.flags = static_cast<std::uint8_t>((valid ? NavPvt::kGnssFixOk : 0) |
                                        (mode_ == ReceiverMode::kDgps ? NavPvt::kDiffSoln : 0) |
                                        (mode_ == ReceiverMode::kRtkFixed && valid ? 0x80 : 0));
    m.flags2 = NavPvt::kConfirmedAvai | NavPvt::kConfirmedDate | NavPvt::kConfirmedTime;
    m.num_sv = static_cast<std::uint8_t>(fix.num_used);
    if (valid) {
      m.lon_1e7deg = clamp_cast<std::int32_t>(fix.position.lon_deg * 1e7);
      m.lat_1e7deg = clamp_cast<std::int32_t>(fix.position.lat_deg * 1e7);
      m.height_mm = clamp_cast<std::int32_t>(fix.position.h_m * 1e3);
      m.h_msl_mm = clamp_cast<std::int32_t>((fix.position.h_m - separation_m) * 1e3);
    } else {
      m.flags3 = 0x01;  // invalidLlh
    }
    m.h_acc_mm = clamp_cast<std::uint32_t>(acc.h_m * 1e3);
    m.v_acc_mm = clamp_cast<std::uint32_t>(acc.v_m * 1e3);
    m.vel_n_mmps = clamp_cast<std::int32_t>(v_ned.x() * 1e3);
    m.vel_e_mmps = clamp_cast<std::int32_t>(v_ned.y() * 1e3);
    m.vel_d_mmps = clamp_cast<std::int32_t>(v_ned.z() * 1e3);
    m.g_speed_mmps = clamp_cast<std::int32_t>(g_speed * 1e3);
    m.head_mot_1e5deg = clamp_cast<std::int32_t>(heading_deg * 1e5);
    m.s_acc_mmps = clamp_cast<std::uint32_t>(acc.s_mps * 1e3);
    const double head_acc_deg = g_speed > acc.s_mps ? std::atan2(acc.s_mps, g_speed) * kRadToDeg : 180.0;
    m.head_acc_1e5deg = clamp_cast<std::uint32_t>(head_acc_deg * 1e5);
    m.p_dop_0p01 = clamp_cast<std::uint16_t>(valid ? fix.dops.pdop * 100.0 : 9999.0);
    append(m, out);
  } else if (id == kNavPosllh) {
    NavPosllh m;
    m.i_tow_ms = i_tow;
    m.lon_1e7deg = clamp_cast<std::int32_t>(fix.position.lon_deg * 1e7);
    m.lat_1e7deg = clamp_cast<std::int32_t>(fix.position.lat_deg * 1e7);
    m.height_mm = clamp_cast<std::int32_t>(fix.position.h_m * 1e3);
    m.h_msl_mm = clamp_cast<std::int32_t>((fix.position.h_m - separation_m) * 1e3);
    m.h_acc_mm = clamp_cast<std::uint32_t>(acc.h_m * 1e3);
    m.v_acc_mm = clamp_cast<std::uint32_t>(acc.v_m * 1e3);
    append(m, out);
  } else if (id == kNavPosecef) {
    NavPosecef m;
    m.i_tow_ms = i_tow;
    m.ecef_x_cm = clamp_cast<std::int32_t>(fix.p_ecef_m.x() * 100.0);
    m.ecef_y_cm = clamp_cast<std::int32_t>(fix.p_ecef_m.y() * 100.0);
    m.ecef_z_cm = clamp_cast<std::int32_t>(fix.p_ecef_m.z() * 100.0);
    m.p_acc_cm = clamp_cast<std::uint32_t>(acc.p_m * 100.0);
    append(m, out);
  } else if (id == kNavVelned) {
    NavVelned m;
    m.i_tow_ms = i_tow;
    m.vel_n_cmps = clamp_cast<std::int32_t>(v_ned.x() * 100.0);
    m.vel_e_cmps = clamp_cast<std::int32_t>(v_ned.y() * 100.0);
    m.vel_d_cmps = clamp_cast<std::int32_t>(v_ned.z() * 100.0);
    m.speed_cmps = clamp_cast<std::uint32_t>(v_ned.norm() * 100.0);
    m.g_speed_cmps = clamp_cast<std::uint32_t>(g_speed * 100.0);
    m.heading_1e5deg = clamp_cast<std::int32_t>(heading_deg * 1e5);
    m.s_acc_cmps = clamp_cast<std::uint32_t>(acc.s_mps * 100.0);
    m.c_acc_1e5deg = clamp_cast<std::uint32_t>(180.0 * 1e5);
    append(m, out);
  } else if (id == kNavVelecef) {
    NavVelecef m;
    m.i_tow_ms = i_tow;
    m.ecef_vx_cmps = clamp_cast<std::int32_t>(v_ecef.x() * 100.0);
    m.ecef_vy_cmps = clamp_cast<std::int32_t>(v_ecef.y() * 100.0);
    m.ecef_vz_cmps = clamp_cast<std::int32_t>(v_ecef.z() * 100.0);
    m.s_acc_cmps = clamp_cast<std::uint32_t>(acc.s_mps * 100.0);
    append(m, out);
  } else if (id == kNavStatus) {
    NavStatus m;
    m.i_tow_ms = i_tow;
    m.gps_fix = fix_type(fix.fix);
    m.flags = status_flags;
    m.ttff_ms = 1000;
    m.msss_ms = i_tow;
    append(m, out);
  } else if (id == kNavSol) {
    NavSol m;
    m.i_tow_ms = i_tow;
    m.f_tow_ns = clamp_cast<std::int32_t>((wt.tow_s * 1000.0 - std::round(wt.tow_s * 1000.0)) * 1e6);
    m.week = static_cast<std::int16_t>(wt.week);
    m.gps_fix = fix_type(fix.fix);
    m.flags = status_flags;
    m.ecef_x_cm = clamp_cast<std::int32_t>(fix.p_ecef_m.x() * 100.0);
    m.ecef_y_cm = clamp_cast<std::int32_t>(fix.p_ecef_m.y() * 100.0);
    m.ecef_z_cm = clamp_cast<std::int32_t>(fix.p_ecef_m.z() * 100.0);
    m.p_acc_cm = clamp_cast<std::uint32_t>(acc.p_m * 100.0);
    m.ecef_vx_cmps = clamp_cast<std::int32_t>(v_ecef.x() * 100.0);
    m.ecef_vy_cmps = clamp_cast<std::int32_t>(v_ecef.y() * 100.0);
    m.ecef_vz_cmps = clamp_cast<std::int32_t>(v_ecef.z() * 100.0);
    m.s_acc_cmps = clamp_cast<std::uint32_t>(acc.s_mps * 100.0);
    m.p_dop_0p01 = clamp_cast<std::uint16_t>(valid ? fix.dops.pdop * 100.0 : 9999.0);
    m.num_sv = static_cast<std::uint8_t>(fix.num_used);
    append(m, out);
  } else if (id == kNavDop) {
    NavDop m;
    m.i_tow_ms = i_tow;
    const double k = valid ? 100.0 : 0.0;
    m.g_dop_0p01 = clamp_cast<std::uint16_t>(valid ? fix.dops.gdop * k : 9999.0);
    m.p_dop_0p01 = clamp_cast<std::uint16_t>(valid ? fix.dops.pdop * k : 9999.0);
    m.t_dop_0p01 = clamp_cast<std::uint16_t>(valid ? fix.dops.tdop * k : 9999.0);
    m.v_dop_0p01 = clamp_cast<std::uint16_t>(valid ? fix.dops.vdop * k : 9999.0);
    m.h_dop_0p01 = clamp_cast<std::uint16_t>(valid ? fix.dops.hdop * k : 9999.0);
    // Without the full covariance, north and east share the horizontal DOP equally.
    m.n_dop_0p01 = clamp_cast<std::uint16_t>(valid ? fix.dops.hdop / std::sqrt(2.0) * k : 9999.0);
    m.e_dop_0p01 = m.n_dop_0p01;
    append(m, out);
  } else if (id == kNavTimegps) {
    NavTimegps m;
    m.i_tow_ms = i_tow;
    m.week = static_cast<std::int16_t>(wt.week);
    m.leap_s = static_cast<std::int8_t>(leap_s);
    m.valid = NavTimegps::kTowValid | NavTimegps::kWeekValid | NavTimegps::kLeapSValid;
    m.t_acc_ns = 20;
    append(m, out);
  } else if (id == kNavTimeutc) {
    const CalendarTime c = utc_from_gps(fix.t);
    const double whole = std::floor(c.second);
    NavTimeutc m;
    m.i_tow_ms = i_tow;
    m.t_acc_ns = 20;
    m.nano_ns = static_cast<std::int32_t>(std::lround((c.second - whole) * 1e9));
    m.year = static_cast<std::uint16_t>(c.year);
    m.month = static_cast<std::uint8_t>(c.month);
    m.day = static_cast<std::uint8_t>(c.day);
    m.hour = static_cast<std::uint8_t>(c.hour);
    m.min = static_cast<std::uint8_t>(c.minute);
    m.sec = static_cast<std::uint8_t>(whole);
    m.valid = NavTimeutc::kValidTow | NavTimeutc::kValidWkn | NavTimeutc::kValidUtc | (3 << 4);
    append(m, out);
  } else if (id == kNavClock) {
    NavClock m;
    m.i_tow_ms = i_tow;
    m.clk_b_ns = clamp_cast<std::int32_t>(meas.rx_clock_bias_s * 1e9);
    m.clk_d_nsps = clamp_cast<std::int32_t>(meas.rx_clock_drift_sps * 1e9);
    m.t_acc_ns = 20;
    m.f_acc_psps = 500;
    append(m, out);
  } else if (id == kNavSvinfo) {
    NavSvinfo& m = reset_keeping_storage(scratch_svinfo_, &NavSvinfo::channels);
    m.i_tow_ms = i_tow;
    m.global_flags = 4;  // u-blox 8 generation
    std::uint8_t chn = 0;
    for (const ReceiverSatellite& s : fix.satellites) {
      NavSvinfoChannel c;
      c.chn = chn++;
      c.svid = static_cast<std::uint8_t>(s.prn);
      c.flags = static_cast<std::uint8_t>((s.used ? NavSvinfoChannel::kSvUsed : 0) |
                                          NavSvinfoChannel::kOrbitAvail | NavSvinfoChannel::kOrbitEph);
      c.quality = 7;  // code and carrier locked, time synchronised
      c.cno_dbhz = clamp_cast<std::uint8_t>(s.cn0_dbhz);
      c.elev_deg = clamp_cast<std::int8_t>(s.el_deg);
      c.azim_deg = clamp_cast<std::int16_t>(s.az_deg);
      m.channels.push_back(c);
    }
    append(m, out);
  } else if (id == kNavSat) {
    NavSat& m = reset_keeping_storage(scratch_sat_, &NavSat::svs);
    m.i_tow_ms = i_tow;
    for (const ReceiverSatellite& s : fix.satellites) {
      NavSatSv v;
      v.gnss_id = 0;
      v.sv_id = static_cast<std::uint8_t>(s.prn);
      v.cno_dbhz = clamp_cast<std::uint8_t>(s.cn0_dbhz);
      v.elev_deg = clamp_cast<std::int8_t>(s.el_deg);
      v.azim_deg = clamp_cast<std::int16_t>(s.az_deg);
      v.flags = 7u | (s.used ? NavSatSv::kSvUsed : 0u) | (1u << NavSatSv::kHealthShift) |
                (1u << NavSatSv::kOrbitSourceShift) | NavSatSv::kEphAvail;
      m.svs.push_back(v);
    }
    append(m, out);
  } else if (id == kNavEoe) {
    append(NavEoe{i_tow}, out);
  } else if (id == kRxmRawx) {
    const WeekTow rt = to_week_tow(meas.t_receiver);
    RxmRawx& m = reset_keeping_storage(scratch_rawx_, &RxmRawx::meas);
    m.rcv_tow_s = rt.tow_s;
    m.week = static_cast<std::uint16_t>(rt.week);
    m.leap_s = static_cast<std::int8_t>(leap_s);
    m.rec_stat = RxmRawx::kLeapSec;
    for (const SatMeasurement& s : meas.sats) {
      if (!s.signals[0]) continue;
      const SignalObs& o = *s.signals[0];
      RxmRawxMeas r;
      r.pr_mes_m = o.pseudorange_m;
      r.cp_mes_cycles = o.carrier_cycles;
      r.do_mes_hz = static_cast<float>(o.doppler_hz);
      r.gnss_id = 0;
      r.sv_id = static_cast<std::uint8_t>(s.prn);
      r.locktime_ms = static_cast<std::uint16_t>(std::min(o.lock_time_s * 1000.0, kMaxLockTime_ms));
      r.cno_dbhz = clamp_cast<std::uint8_t>(o.cn0_dbhz);
      r.pr_stdev = 5;  // 0.01 * 2^5 = 0.32 m
      r.cp_stdev = 3;  // 0.012 cycles
      r.do_stdev = 6;  // 0.128 Hz
      r.trk_stat = RxmRawxMeas::kPrValid | RxmRawxMeas::kCpValid | RxmRawxMeas::kHalfCyc |
                   RxmRawxMeas::kSubHalfCyc;
      (void)used;
      m.meas.push_back(r);
    }
    append(m, out);
  } else if (id == kRxmSfrbx) {
    // A subframe is complete every 6 s of GPS time (IS-GPS-200 20.3.2): at such an epoch, each
    // tracked satellite's subframe that just ended, regenerated from the ephemeris in use.
    const auto tow_ms = static_cast<std::int64_t>(std::llround(wt.tow_s * 1000.0));
    if (tow_ms % 6000 != 0) return true;
    const auto tow_count_next = static_cast<std::uint32_t>(tow_ms / 6000) % lnav::kTowCountsPerWeek;
    const std::uint32_t tow_count_this = (tow_count_next + lnav::kTowCountsPerWeek - 1) % lnav::kTowCountsPerWeek;
    const int sf_id = static_cast<int>(tow_count_this % 5) + 1;
    const int page = static_cast<int>((tow_count_this / 5) % 25) + 1;
    lnav::LnavIonoUtc iono;
    if (nav_.klobuchar) {
      iono.alpha = nav_.klobuchar->alpha;
      iono.beta = nav_.klobuchar->beta;
    }
    iono.dt_ls_s = leap_s;
    iono.dt_lsf_s = leap_s;
    iono.wnt = wt.week;
    iono.wn_lsf = wt.week;
    iono.dn = 1;
    std::uint8_t chn = 0;
    for (const SatMeasurement& s : meas.sats) {
      if (s.eph == nullptr) continue;
      RxmSfrbx& m = reset_keeping_storage(scratch_sfrbx_, &RxmSfrbx::words);
      m.gnss_id = 0;
      m.sv_id = static_cast<std::uint8_t>(s.prn);
      m.chn = chn++;
      const lnav::LnavSubframe w = lnav::lnav_subframe(sf_id, tow_count_next, to_lnav(*s.eph), iono, page);
      m.words.assign(w.begin(), w.end());
      append(m, out);
    }
  } else {
    return false;
  }
  return true;
}

void UbxDevice::encode_epoch(const ReceiverFix& fix_in, const EpochMeasurements& meas,
                             std::int64_t epoch_index, std::string& out) {
  last_fix_ = fix_in;
  last_meas_ = meas;
  if (restarting(fix_in.t)) {  // after CFG-RST: searching, no fix and no satellites yet
    reset_keeping_storage(last_fix_, &ReceiverFix::satellites).t = fix_in.t;
    last_meas_.sats.clear();
  }
  if (out_proto_ & kProtoUbx) {
    scratch_.clear();
    for (const OutputMessage& m : kOutputs) {
      const int r = rate(m.id);
      if (r > 0 && epoch_index % r == 0) output_message(m.id, scratch_);
    }
    out.append(reinterpret_cast<const char*>(scratch_.data()), scratch_.size());
  }
  if (out_proto_ & kProtoNmea) nmea_->encode(last_fix_, epoch_index, out);
}

// ---- The device of a profile ----------------------------------------------------------------

namespace {
class NmeaDevice final : public GnssDevice {
 public:
  NmeaDevice(const GnssProfile& p, ReceiverMode mode)
      : out_(p, mode), period_ns_(std::llround(1e9 / p.rate_hz)) {}
  void encode_epoch(const ReceiverFix& fix, const EpochMeasurements&, std::int64_t epoch_index,
                    std::string& out) override {
    out_.encode(fix, epoch_index, out);
  }
  std::int64_t period_ns() const override { return period_ns_; }

 private:
  NmeaOutput out_;
  std::int64_t period_ns_;
};
}  // namespace

std::unique_ptr<GnssDevice> make_gnss_device(const GnssProfile& profile, ReceiverMode mode,
                                             const NavData& nav) {
  if (profile.ubx) return std::make_unique<UbxDevice>(profile, mode, nav);
  return std::make_unique<NmeaDevice>(profile, mode);
}

}  // namespace navemu
