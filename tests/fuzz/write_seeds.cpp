// Writes the seed inputs of the binary fuzz targets, built with navemu's own encoders:
// `navemu-fuzz-seeds DIR` fills DIR/ubx_device (the configuration handshake gpsd, ubxtool and
// u-center send: polls, CFG-PRT/MSG/RATE/NAV5/GNSS/CFG/RST, CFG-VALSET/VALGET/VALDEL, NMEA
// in between), DIR/slcan (python-can's opening sequence, every command letter, frames of each
// kind), DIR/truth_datagram (binary and JSON truth datagrams of every form), DIR/scene (a
// building on a ground sheet, since the mission city is generated, not kept) and
// DIR/nav_messages (every unit of the GPS, Galileo, GLONASS and BeiDou navigation messages). The other text
// targets' seeds are files of the project and of ../shared (tools/fuzz).

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "protocols/beidou_nav.hpp"
#include "protocols/galileo_inav.hpp"
#include "protocols/glonass_nav.hpp"
#include "protocols/gps_lnav.hpp"
#include "protocols/truth_datagram.hpp"
#include "protocols/ubx.hpp"
#include "protocols/ubx_messages.hpp"

namespace {

namespace fs = std::filesystem;

void write(const fs::path& dir, const std::string& name, std::string_view bytes) {
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}
void write(const fs::path& dir, const std::string& name, const std::vector<std::uint8_t>& bytes) {
  write(dir, name, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

template <typename Msg>
std::vector<std::uint8_t> frame(const Msg& m) {
  std::vector<std::uint8_t> out;
  navemu::ubx::append(m, out);
  return out;
}

// Byte 0 of a ubx_device input picks the profile (bit 0) and the cut; the rest is the stream.
void write_ubx(const fs::path& dir, const std::string& name, std::vector<std::uint8_t> stream) {
  for (const std::uint8_t selector : {std::uint8_t{0x10}, std::uint8_t{0x11}}) {
    std::vector<std::uint8_t> input{selector};
    input.insert(input.end(), stream.begin(), stream.end());
    write(dir, name + ((selector & 1) != 0 ? "-f9p" : "-m8"), input);
  }
}

void ubx_seeds(const fs::path& dir) {
  namespace ubx = navemu::ubx;
  std::vector<std::uint8_t> handshake;
  for (const ubx::MsgId id : {ubx::kMonVer, ubx::kCfgPrt, ubx::kCfgRate, ubx::kCfgNav5, ubx::kCfgGnss,
                              ubx::kMonHw, ubx::kNavPvt, ubx::kNavSat, ubx::kSecUniqid})
    ubx::append_poll(id, handshake);
  write_ubx(dir, "polls", handshake);

  ubx::CfgPrt prt;
  prt.port_id = ubx::kPortUart1;
  prt.mode = ubx::CfgPrt::kMode8N1;
  prt.baud_rate = 115200;
  prt.in_proto_mask = ubx::kProtoUbx;
  prt.out_proto_mask = ubx::kProtoUbx | ubx::kProtoNmea;
  write_ubx(dir, "cfg-prt", frame(prt));

  std::vector<std::uint8_t> rates;
  for (const ubx::MsgId id : {ubx::kNavPvt, ubx::kNavSat, ubx::kRxmRawx, ubx::kRxmSfrbx, ubx::kNavEoe}) {
    ubx::CfgMsg m;
    m.msg_class = id.cls;
    m.msg_id = id.id;
    m.rate[ubx::kPortUart1] = 1;
    ubx::append(m, rates);
  }
  ubx::CfgMsgCurrentPort current;
  current.msg_class = ubx::kNavDop.cls;
  current.msg_id = ubx::kNavDop.id;
  current.rate = 2;
  ubx::append(current, rates);
  ubx::CfgMsgPoll msg_poll;
  msg_poll.msg_class = ubx::kNavPvt.cls;
  msg_poll.msg_id = ubx::kNavPvt.id;
  ubx::append(msg_poll, rates);
  write_ubx(dir, "cfg-msg", rates);

  ubx::CfgRate rate;
  rate.meas_rate_ms = 200;
  write_ubx(dir, "cfg-rate", frame(rate));

  ubx::CfgNav5 nav5;
  nav5.mask = ubx::CfgNav5::kMaskDyn | ubx::CfgNav5::kMaskMinEl;
  nav5.dyn_model = 4;
  nav5.min_elev_deg = 10;
  write_ubx(dir, "cfg-nav5", frame(nav5));

  ubx::CfgGnss gnss;
  gnss.num_trk_ch_use = 32;
  gnss.blocks = {{0, 8, 16, 0, ubx::CfgGnssBlock::kEnable | (1u << ubx::CfgGnssBlock::kSigCfgMaskShift)},
                 {6, 4, 8, 0, 0}};
  write_ubx(dir, "cfg-gnss", frame(gnss));

  ubx::CfgCfg cfg;
  cfg.save_mask = 0x1F1F;
  cfg.has_device_mask = true;
  cfg.device_mask = 0x17;
  write_ubx(dir, "cfg-cfg", frame(cfg));

  ubx::CfgRst rst;
  rst.nav_bbr_mask = ubx::CfgRst::kColdStart;
  rst.reset_mode = ubx::CfgRst::kControlledSoftwareResetGnss;
  write_ubx(dir, "cfg-rst", frame(rst));

  namespace key = ubx::cfgkey;
  ubx::CfgValset valset;
  valset.values = {{key::kRateMeas, 100}, {key::kUart1Baudrate, 230400}, {key::kUart1outprotUbx, 1},
                   {key::kMsgoutUbxNavDopUart1, 1}, {key::kNavspgDynmodel, 2}};
  ubx::CfgValgetRequest valget;
  valget.keys = {key::kRateMeas, key::kRateNav, key::kUart1Baudrate, 0x0FFF0000};
  ubx::CfgValdel valdel;
  valdel.keys = {key::kRateMeas};
  std::vector<std::uint8_t> keys = frame(valset);
  ubx::append(valget, keys);
  ubx::append(valdel, keys);
  write_ubx(dir, "cfg-val", keys);

  // Layers, transactions and wildcards (UBX-18010854 6.2-6.4): a three-part transaction into
  // BBR and Flash, a group read from the Default layer with paging, a group deleted.
  std::vector<std::uint8_t> layered;
  for (const std::uint8_t txn : {std::uint8_t{1}, std::uint8_t{2}, std::uint8_t{3}}) {
    ubx::CfgValset part;
    part.version = 1;
    part.layers = ubx::kLayerMaskRam | ubx::kLayerMaskBbr | ubx::kLayerMaskFlash;
    part.transaction = txn;
    part.values = {{key::kRateMeas, 100u * txn}, {0x40050002, 500000}};
    ubx::append(part, layered);
  }
  ubx::CfgValgetRequest group;
  group.layer = ubx::kLayerDefault;
  group.position = 64;
  group.keys = {0x0fffffff, 0x0021ffff};
  ubx::append(group, layered);
  ubx::CfgValdel del;
  del.version = 1;
  del.layers = ubx::kLayerMaskBbr;
  del.keys = {0x0021ffff};
  ubx::append(del, layered);
  write_ubx(dir, "cfg-layers", layered);

  // Multi-block legacy forms: CFG-PRT for UART1 and USB in one message (PX4's driver), CFG-INF
  // for both protocols, CFG-TP5 poll by index and set, CFG-NMEA's short form.
  ubx::CfgPrtPorts ports;
  ports.ports = {prt, prt};
  ports.ports[1].port_id = ubx::kPortUsb;
  std::vector<std::uint8_t> legacy = frame(ports);
  ubx::CfgInf inf;
  inf.blocks = {{0, {}, {0, 1, 0, 1, 0, 0}}, {1, {}, {0, 7, 0, 7, 0, 0}}};
  ubx::append(inf, legacy);
  ubx::append(ubx::CfgInfPoll{1}, legacy);
  ubx::CfgTp5 tp5;
  tp5.tp_idx = 1;
  tp5.freq_period_hz_or_us = 10;
  ubx::append(tp5, legacy);
  ubx::append_frame(ubx::kCfgTp5.cls, ubx::kCfgTp5.id, std::vector<std::uint8_t>{1}, legacy);
  ubx::append_frame(ubx::kCfgNmea.cls, ubx::kCfgNmea.id, std::vector<std::uint8_t>{0, 0x23, 0, 0}, legacy);
  for (const ubx::MsgId id : {ubx::kCfgSbas, ubx::kCfgNavx5, ubx::kCfgItfm, ubx::kCfgTmode3, ubx::kCfgGeofence})
    ubx::append_poll(id, legacy);
  write_ubx(dir, "cfg-legacy", legacy);

  // The time mode and output filters: survey-in by items and by CFG-TMODE3, NAV-SVIN polled;
  // a tight PDOP mask; epochs on UTC's grid at 700 ms.
  std::vector<std::uint8_t> modes;
  ubx::CfgValset survey;
  survey.values = {{0x20030001, 1}, {0x40030010, 2}, {0x40030011, 100000}, {0x301100b1, 15}};
  ubx::append(survey, modes);
  ubx::CfgTmode3 tmode3;
  tmode3.flags = 1;
  tmode3.svin_min_dur_s = 3;
  tmode3.svin_acc_limit_0p1mm = 50000;
  ubx::append(tmode3, modes);
  ubx::CfgTmode3 fixed;  // then a fixed position, LLH with HP parts: the time-only fix
  fixed.flags = 2 | ubx::CfgTmode3::kLla;
  fixed.ecef_x_or_lat = 323'000'000;
  fixed.ecef_y_or_lon = -909'000'000;
  fixed.ecef_z_or_alt_cm = 6'000;
  fixed.ecef_x_or_lat_hp = -99;
  fixed.fixed_pos_acc_0p1mm = 1'000;
  ubx::append(fixed, modes);
  ubx::append(ubx::CfgRate{700, 1, ubx::CfgRate::kTimeRefUtc}, modes);
  for (const ubx::MsgId id : {ubx::kNavSvin, ubx::kCfgTmode3, ubx::kCfgNmea, ubx::kCfgOdo, ubx::kNavPvt})
    ubx::append_poll(id, modes);
  write_ubx(dir, "time-mode", modes);

  // Aiding data, the navigation database and its backup: the AID polls of all satellites and of
  // one, the MGA-DBD dump, UPD-SOS poll, create and clear, a reset between, RXM-MEASX.
  std::vector<std::uint8_t> aiding;
  for (const ubx::MsgId id : {ubx::kAidIni, ubx::kAidHui, ubx::kAidAlm, ubx::kAidEph, ubx::kAidAop,
                              ubx::kMgaDbd, ubx::kUpdSos, ubx::kRxmMeasx, ubx::kRxmImes})
    ubx::append_poll(id, aiding);
  for (const ubx::MsgId id : {ubx::kAidAlm, ubx::kAidEph, ubx::kAidAop})
    ubx::append_frame(id.cls, id.id, std::vector<std::uint8_t>{7}, aiding);
  ubx::append(ubx::UpdSosCommand{ubx::UpdSosCommand::kCreate, {}}, aiding);
  ubx::append(ubx::CfgRst{ubx::CfgRst::kHotStart, ubx::CfgRst::kHardwareReset, 0}, aiding);
  ubx::append_poll(ubx::kUpdSos, aiding);
  ubx::append(ubx::UpdSosCommand{ubx::UpdSosCommand::kClear, {}}, aiding);
  // Acknowledged assistance: ackAiding by item and by CFG-NAVX5, MGA-INI-TIME_UTC, a DBD entry.
  ubx::CfgValset ack_aiding;
  ack_aiding.values = {{0x10110025, 1}};
  ubx::append(ack_aiding, aiding);
  ubx::CfgNavx5 navx5;
  navx5.mask1 = 1u << 10;
  navx5.ack_aiding = 1;
  ubx::append(navx5, aiding);
  std::vector<std::uint8_t> ini_time(24, 0);
  ini_time[0] = 0x10;
  ubx::append_frame(ubx::kClassMga, 0x40, ini_time, aiding);
  ubx::MgaDbd dbd;
  dbd.data = {1, 7, 0, 0, 0};
  ubx::append(dbd, aiding);
  write_ubx(dir, "aiding", aiding);

  // NMEA commands and noise between frames, and a frame cut short.
  std::vector<std::uint8_t> mixed;
  for (const char c : std::string_view("$PUBX,40,GSV,0,0,0,0,0,0*59\r\n$GPGGA,,*56\r\n\xB5\x62\x06"))
    mixed.push_back(static_cast<std::uint8_t>(c));
  ubx::append_poll(ubx::kMonVer, mixed);
  mixed.resize(mixed.size() - 3);
  write_ubx(dir, "mixed", mixed);

  // The NMEA input the part takes (UBX-13003221 "PUBX Messages", standard polls).
  std::vector<std::uint8_t> nmea_in;
  for (const char c : std::string_view("$PUBX,40,GLL,1,0,0,0,0,0*5D\r\n$PUBX,00*33\r\n$PUBX,03*30\r\n"
                                       "$PUBX,04*37\r\n$EIGPQ,RMC*3A\r\n$PUBX,41,1,0001,0001,38400,0*24\r\n"))
    nmea_in.push_back(static_cast<std::uint8_t>(c));
  write_ubx(dir, "nmea-input", nmea_in);
}

void slcan_seeds(const fs::path& dir) {
  // Byte 0: bit 7 opens the channel from the start, bits 0..5 set the piece size.
  const std::vector<std::pair<std::string, std::string>> seeds = {
      {"python-can-open", "\x05\r\r\rC\rS6\rO\r"},
      {"queries", "\x3F" "V\rv\rN\rF\rZ1\rZ0\rM00000000\rm00000000\rX1\rW2\rQ0\r"},
      {"bitrates", "\x02" "S0\rS8\rS9\rs031C\rs03\rO\rS4\rC\r"},
      {"frames", "\x80" "t1238112233445566778\rT1234567811A\rr1230\rR123456780\rt7FF0\r"},
      {"fd-frames", "\x80" "d123F" + std::string(128, 'A') + "\rB12345678C" + std::string(48, '0') + "\rb1239" +
                        std::string(24, 'F') + "\r"},
      {"errors", "\x01" "O\rO\rt800\rT2000000010\rt12390011223344556677\rd12310\rx\r\n\r" + std::string(150, 't') +
                     "\r"},
  };
  for (const auto& [name, bytes] : seeds) write(dir, name, bytes);
}

void truth_seeds(const fs::path& dir) {
  namespace td = navemu::truth_datagram;
  td::Message m;
  m.sequence = 7;
  m.time_ns = 1'277'000'000'000'000'000;
  m.position = {55.7, 12.5, 40.0};
  m.velocity_mps = {10.0, -2.0, 0.1};
  m.attitude = {0.96, 0.0, 0.0, 0.28};
  write(dir, "geodetic-quaternion.bin", std::string_view(reinterpret_cast<const char*>(td::encode_binary(m).data()),
                                                          td::kBinarySize));
  write(dir, "geodetic-quaternion.json", td::encode_json(m));

  m.time_base = td::TimeBase::kHostUtc;
  m.position_frame = td::PositionFrame::kEcef;
  m.position = {3'513'649.6, 778'954.5, 5'248'201.8};
  m.velocity_frame = td::VelocityFrame::kEcef;
  m.attitude_form = td::AttitudeForm::kRollPitchYaw;
  m.attitude = {1.0, -2.0, 135.0, 0.0};
  m.has_rates = true;
  m.f_body_mps2 = {0.1, 0.2, -9.8};
  m.w_body_radps = {0.01, 0.0, 0.3};
  m.has_temperature = true;
  m.temperature_c = 31.5;
  write(dir, "ecef-rpy-rates.bin", std::string_view(reinterpret_cast<const char*>(td::encode_binary(m).data()),
                                                     td::kBinarySize));
  write(dir, "ecef-rpy-rates.json", td::encode_json(m));
}

// A building on a ground sheet, as `navemu scene` writes them (emulator/scene_loader.hpp).
void scene_seeds(const fs::path& dir) {
  write(dir, "building.obj",
        "# ground and a 10 m cube\nmtllib materials.mtl\n"
        "v -50 -50 0\nv 50 -50 0\nv 50 50 0\nv -50 50 0\n"
        "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nv 0 0 10\nv 10 0 10\nv 10 10 10\nv 0 10 10\n"
        "g ground\nusemtl ground\nf 1 2 3 4\n"
        "g building\nusemtl concrete\nf 5 6 10 9\nf 6 7 11 10\nf 7 8 12 11\nf 8 5 9 12\n"
        "usemtl glass\nf 9 10 11 12\nf 5 8 7 6\n");
}

// nav_messages records (tests/fuzz/fuzz_nav_messages.cpp): gnssId, number of words, words.
void record(std::vector<std::uint8_t>& out, int gnss_id, std::span<const std::uint32_t> words) {
  out.push_back(static_cast<std::uint8_t>(gnss_id));
  out.push_back(static_cast<std::uint8_t>(words.size()));
  for (const std::uint32_t w : words)
    for (int b = 0; b < 4; ++b) out.push_back(static_cast<std::uint8_t>(w >> (8 * b)));
}

// Plausible broadcast values (a medium Earth orbit), the same shape for every system.
template <typename Eph>
Eph kepler(navemu::SatId sat, navemu::GpsTime toe) {
  Eph e;
  e.sat = sat;
  e.toe = e.toc = toe;
  e.sqrt_a_sqrtm = 5440.6;
  e.e = 0.0003;
  e.i0_rad = 0.98;
  e.omega0_rad = -1.2;
  e.omega_rad = 0.4;
  e.m0_rad = 2.1;
  e.delta_n_radps = 3e-9;
  e.omega_dot_radps = -5.6e-9;
  e.af0_s = -4.1e-4;
  e.af1_sps = -7e-12;
  return e;
}

void nav_message_seeds(const fs::path& dir) {
  using namespace navemu;
  const GpsTime toe = from_week_tow(2111, 345600.0);
  const int leap_s = 18;

  std::vector<std::uint8_t> gps;
  lnav::LnavEphemeris l;
  l.sv_id = 5;
  l.week = 2111;
  l.iodc = l.iode = 33;
  l.toc_s = l.toe_s = 345600.0;
  l.sqrt_a_sqrtm = 5153.6;
  l.e = 0.01;
  l.i0_rad = 0.96;
  const lnav::LnavIonoUtc iono;
  for (std::uint32_t count = 57600; count < 57600 + 50; ++count) {  // 10 frames of pages
    const int sf = lnav::lnav_subframe_id_for(count);
    record(gps, 0, lnav::lnav_subframe(sf, count, l, iono, lnav::lnav_page_for(count)));
  }
  write(dir, "gps-lnav", gps);

  std::vector<std::uint8_t> gal;
  auto e = kepler<GalileoEphemeris>(SatId(GnssSystem::kGalileo, 11), toe);
  e.iod_nav = 61;
  e.sisa_m = 3.12;
  inav::InavSystemData sys;
  sys.ai0_sfu = 28.25;
  sys.dt_ls_s = sys.dt_lsf_s = leap_s;
  sys.a0g_s = 2.36e-9;
  for (double tow = 345601.0; tow < 345601.0 + 60.0; tow += 2.0)
    record(gal, 2, inav::inav_page(inav::inav_word_type_for(tow), 2111 - kGstWeek0InGpsWeeks, tow, e, sys));
  write(dir, "galileo-inav", gal);

  std::vector<std::uint8_t> glo;
  GlonassEphemeris g;
  g.sat = SatId(GnssSystem::kGlonass, 1);
  g.tb = toe.plus_s(900.0);
  g.p_pz90_m = Vec3(10908942.4, -2885726.1, 22883539.6);
  g.v_pz90_mps = Vec3(1407.8, 2795.9, -317.0);
  g.tau_n_s = -6.4e-5;
  g.frequency_channel = 1;
  gnav::GnavSystemData gs;
  gs.n_a = 1271;
  gs.n4 = 7;
  const std::array<gnav::GnavAlmanacEntry, 1> almanac{gnav::GnavAlmanacEntry{.slot = 2, .h_a = -4}};
  for (double t = 0.0; t < 150.0; t += 2.0) {
    const gnav::GnavSlot slot = gnav::glonass_slot(toe.plus_s(t), leap_s);
    gnav::GnavImmediateFlags flags;
    flags.frame_time_s = slot.frame_time_s;
    record(glo, 6, gnav::glonass_string(slot.frame, slot.string, g, flags, leap_s, gs, almanac, slot.superframe));
  }
  write(dir, "glonass-strings", glo);

  std::vector<std::uint8_t> d1, d2;
  auto b = kepler<BeidouEphemeris>(SatId(GnssSystem::kBeidou, 11), toe);
  const bdnav::BdsBroadcast bc;
  for (double sow = 345600.0; sow < 345600.0 + 60.0; sow += 6.0) {
    const bdnav::BdsSlot slot = bdnav::d1_slot_at(sow);
    record(d1, 3, bdnav::d1_subframe(slot.fra_id, slot.page, {2111 - kBdtWeek0InGpsWeeks, slot.sow_s}, b, bc));
  }
  write(dir, "beidou-d1", d1);
  b.sat = SatId(GnssSystem::kBeidou, 1);
  for (double sow = 345600.0; sow < 345600.0 + 31.0; sow += 0.6) {
    const bdnav::BdsSlot slot = bdnav::d2_slot_at(sow);
    record(d2, 3, bdnav::d2_subframe(slot.fra_id, slot.page, {2111 - kBdtWeek0InGpsWeeks, slot.sow_s}, b, bc));
  }
  write(dir, "beidou-d2", d2);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: navemu-fuzz-seeds DIR\n");
    return 2;
  }
  const fs::path dir(argv[1]);
  ubx_seeds(dir / "ubx_device");
  slcan_seeds(dir / "slcan");
  truth_seeds(dir / "truth_datagram");
  scene_seeds(dir / "scene");
  nav_message_seeds(dir / "nav_messages");
  std::printf("seeds written to %s\n", dir.c_str());
  return 0;
}
