// Typed UBX messages <-> frames. Byte offsets follow the payload tables of UBX-13003221
// (u-blox 8 / M8, chapter 32) and UBX-18010854 (ZED-F9P, protocol 27, section 5); the
// structure of each function mirrors the table: one Writer call or Reader offset per row.
#include "protocols/ubx_messages.hpp"

#include <algorithm>
#include <charconv>
#include <cstring>

namespace navemu::ubx {
namespace {

// Starts a frame of `msg` in `out`, lets `body` write the payload, closes the frame.
template <typename Body>
void frame(MsgId msg, std::vector<std::uint8_t>& out, Body&& body) {
  const std::size_t start = begin_frame(msg.cls, msg.id, out);
  Writer w(out);
  body(w);
  end_frame(start, out);
}

template <std::size_t N>
void put_bytes(Writer& w, const std::array<std::uint8_t, N>& a) {
  w.bytes(std::span<const std::uint8_t>(a.data(), a.size()));
}

template <std::size_t N>
void get_bytes(const Reader& r, std::size_t off, std::array<std::uint8_t, N>& a) {
  for (std::size_t i = 0; i < N; ++i) a[i] = r.u1(off + i);
}

// Number of repeated blocks an encoder sends: the one-byte count field caps it at 255.
std::size_t block_count(std::size_t n) { return std::min<std::size_t>(n, 255); }

// A fixed-size, NUL-padded character field; at most size - 1 characters so a NUL ends it.
void put_string(Writer& w, const std::string& s, std::size_t size) {
  const std::size_t n = std::min(s.size(), size - 1);
  w.bytes(std::span<const std::uint8_t>(reinterpret_cast<const std::uint8_t*>(s.data()), n));
  w.zeros(size - n);
}

std::string get_string(std::span<const std::uint8_t> p, std::size_t off, std::size_t size) {
  const auto field = p.subspan(off, size);
  const auto end = std::find(field.begin(), field.end(), std::uint8_t{0});
  return std::string(field.begin(), end);
}

// Key/value pairs of VALGET answers and VALSET (UBX-18010854 section 6): key (U4), then
// cfg_value_size(key) value bytes. A reserved size code or a truncated value fails.
void put_key_values(Writer& w, const std::vector<CfgKeyValue>& values) {
  for (const CfgKeyValue& kv : values) {
    w.u4(kv.key_id);
    const std::size_t n = cfg_value_size(kv.key_id);
    for (std::size_t i = 0; i < n; ++i)
      w.u1(static_cast<std::uint8_t>((kv.value >> (8 * i)) & 0xFF));
  }
}

bool get_key_values(std::span<const std::uint8_t> p, std::size_t off,
                    std::vector<CfgKeyValue>& values) {
  values.clear();
  const Reader r(p);
  while (off < p.size()) {
    if (p.size() - off < 4) return false;
    CfgKeyValue kv;
    kv.key_id = r.u4(off);
    off += 4;
    const std::size_t n = cfg_value_size(kv.key_id);
    if (n == 0 || p.size() - off < n) return false;
    for (std::size_t i = 0; i < n; ++i)
      kv.value |= static_cast<std::uint64_t>(p[off + i]) << (8 * i);
    off += n;
    values.push_back(kv);
  }
  return true;
}

bool get_keys(std::span<const std::uint8_t> p, std::size_t off, std::vector<std::uint32_t>& keys) {
  keys.clear();
  if (p.size() < off || (p.size() - off) % 4 != 0) return false;
  const Reader r(p);
  for (; off < p.size(); off += 4) keys.push_back(r.u4(off));
  return true;
}

void put_keys(Writer& w, const std::vector<std::uint32_t>& keys) {
  for (const std::uint32_t k : keys) w.u4(k);
}

// Length check of a message with `header` bytes and then blocks of `block` bytes, whose count
// is the byte at `count_off`.
bool blocks_fit(std::span<const std::uint8_t> p, std::size_t header, std::size_t block,
                std::size_t count_off) {
  return p.size() >= header && p.size() == header + block * p[count_off];
}

}  // namespace

void append_poll(MsgId msg, std::vector<std::uint8_t>& out) {
  append_frame(msg.cls, msg.id, {}, out);
}

// ---- NAV -----------------------------------------------------------------------------------

// UBX-NAV-PVT payload (UBX-13003221 UBX-NAV-PVT; UBX-18010854 section 5.14.11).
void append(const NavPvt& m, std::vector<std::uint8_t>& out) {
  frame(NavPvt::kMsg, out, [&](Writer& w) {
    w.u4(m.i_tow_ms);
    w.u2(m.year);
    w.u1(m.month);
    w.u1(m.day);
    w.u1(m.hour);
    w.u1(m.min);
    w.u1(m.sec);
    w.u1(m.valid);
    w.u4(m.t_acc_ns);
    w.i4(m.nano_ns);
    w.u1(m.fix_type);
    w.u1(m.flags);
    w.u1(m.flags2);
    w.u1(m.num_sv);
    w.i4(m.lon_1e7deg);
    w.i4(m.lat_1e7deg);
    w.i4(m.height_mm);
    w.i4(m.h_msl_mm);
    w.u4(m.h_acc_mm);
    w.u4(m.v_acc_mm);
    w.i4(m.vel_n_mmps);
    w.i4(m.vel_e_mmps);
    w.i4(m.vel_d_mmps);
    w.i4(m.g_speed_mmps);
    w.i4(m.head_mot_1e5deg);
    w.u4(m.s_acc_mmps);
    w.u4(m.head_acc_1e5deg);
    w.u2(m.p_dop_0p01);
    w.u2(m.flags3);
    put_bytes(w, m.reserved1);
    w.i4(m.head_veh_1e5deg);
    w.i2(m.mag_dec_1e2deg);
    w.u2(m.mag_acc_1e2deg);
  });
}

bool decode(std::span<const std::uint8_t> p, NavPvt& m) {
  if (p.size() < NavPvt::kPayloadSize) return false;
  const Reader r(p);
  m.i_tow_ms = r.u4(0);
  m.year = r.u2(4);
  m.month = r.u1(6);
  m.day = r.u1(7);
  m.hour = r.u1(8);
  m.min = r.u1(9);
  m.sec = r.u1(10);
  m.valid = r.u1(11);
  m.t_acc_ns = r.u4(12);
  m.nano_ns = r.i4(16);
  m.fix_type = r.u1(20);
  m.flags = r.u1(21);
  m.flags2 = r.u1(22);
  m.num_sv = r.u1(23);
  m.lon_1e7deg = r.i4(24);
  m.lat_1e7deg = r.i4(28);
  m.height_mm = r.i4(32);
  m.h_msl_mm = r.i4(36);
  m.h_acc_mm = r.u4(40);
  m.v_acc_mm = r.u4(44);
  m.vel_n_mmps = r.i4(48);
  m.vel_e_mmps = r.i4(52);
  m.vel_d_mmps = r.i4(56);
  m.g_speed_mmps = r.i4(60);
  m.head_mot_1e5deg = r.i4(64);
  m.s_acc_mmps = r.u4(68);
  m.head_acc_1e5deg = r.u4(72);
  m.p_dop_0p01 = r.u2(76);
  m.flags3 = r.u2(78);
  get_bytes(r, 80, m.reserved1);
  m.head_veh_1e5deg = r.i4(84);
  m.mag_dec_1e2deg = r.i2(88);
  m.mag_acc_1e2deg = r.u2(90);
  return r.ok();
}

// UBX-NAV-POSLLH payload.
void append(const NavPosllh& m, std::vector<std::uint8_t>& out) {
  frame(NavPosllh::kMsg, out, [&](Writer& w) {
    w.u4(m.i_tow_ms);
    w.i4(m.lon_1e7deg);
    w.i4(m.lat_1e7deg);
    w.i4(m.height_mm);
    w.i4(m.h_msl_mm);
    w.u4(m.h_acc_mm);
    w.u4(m.v_acc_mm);
  });
}

bool decode(std::span<const std::uint8_t> p, NavPosllh& m) {
  if (p.size() < NavPosllh::kPayloadSize) return false;
  const Reader r(p);
  m.i_tow_ms = r.u4(0);
  m.lon_1e7deg = r.i4(4);
  m.lat_1e7deg = r.i4(8);
  m.height_mm = r.i4(12);
  m.h_msl_mm = r.i4(16);
  m.h_acc_mm = r.u4(20);
  m.v_acc_mm = r.u4(24);
  return r.ok();
}

// UBX-NAV-POSECEF payload.
void append(const NavPosecef& m, std::vector<std::uint8_t>& out) {
  frame(NavPosecef::kMsg, out, [&](Writer& w) {
    w.u4(m.i_tow_ms);
    w.i4(m.ecef_x_cm);
    w.i4(m.ecef_y_cm);
    w.i4(m.ecef_z_cm);
    w.u4(m.p_acc_cm);
  });
}

bool decode(std::span<const std::uint8_t> p, NavPosecef& m) {
  if (p.size() < NavPosecef::kPayloadSize) return false;
  const Reader r(p);
  m.i_tow_ms = r.u4(0);
  m.ecef_x_cm = r.i4(4);
  m.ecef_y_cm = r.i4(8);
  m.ecef_z_cm = r.i4(12);
  m.p_acc_cm = r.u4(16);
  return r.ok();
}

// UBX-NAV-VELNED payload.
void append(const NavVelned& m, std::vector<std::uint8_t>& out) {
  frame(NavVelned::kMsg, out, [&](Writer& w) {
    w.u4(m.i_tow_ms);
    w.i4(m.vel_n_cmps);
    w.i4(m.vel_e_cmps);
    w.i4(m.vel_d_cmps);
    w.u4(m.speed_cmps);
    w.u4(m.g_speed_cmps);
    w.i4(m.heading_1e5deg);
    w.u4(m.s_acc_cmps);
    w.u4(m.c_acc_1e5deg);
  });
}

bool decode(std::span<const std::uint8_t> p, NavVelned& m) {
  if (p.size() < NavVelned::kPayloadSize) return false;
  const Reader r(p);
  m.i_tow_ms = r.u4(0);
  m.vel_n_cmps = r.i4(4);
  m.vel_e_cmps = r.i4(8);
  m.vel_d_cmps = r.i4(12);
  m.speed_cmps = r.u4(16);
  m.g_speed_cmps = r.u4(20);
  m.heading_1e5deg = r.i4(24);
  m.s_acc_cmps = r.u4(28);
  m.c_acc_1e5deg = r.u4(32);
  return r.ok();
}

// UBX-NAV-VELECEF payload.
void append(const NavVelecef& m, std::vector<std::uint8_t>& out) {
  frame(NavVelecef::kMsg, out, [&](Writer& w) {
    w.u4(m.i_tow_ms);
    w.i4(m.ecef_vx_cmps);
    w.i4(m.ecef_vy_cmps);
    w.i4(m.ecef_vz_cmps);
    w.u4(m.s_acc_cmps);
  });
}

bool decode(std::span<const std::uint8_t> p, NavVelecef& m) {
  if (p.size() < NavVelecef::kPayloadSize) return false;
  const Reader r(p);
  m.i_tow_ms = r.u4(0);
  m.ecef_vx_cmps = r.i4(4);
  m.ecef_vy_cmps = r.i4(8);
  m.ecef_vz_cmps = r.i4(12);
  m.s_acc_cmps = r.u4(16);
  return r.ok();
}

// UBX-NAV-STATUS payload.
void append(const NavStatus& m, std::vector<std::uint8_t>& out) {
  frame(NavStatus::kMsg, out, [&](Writer& w) {
    w.u4(m.i_tow_ms);
    w.u1(m.gps_fix);
    w.u1(m.flags);
    w.u1(m.fix_stat);
    w.u1(m.flags2);
    w.u4(m.ttff_ms);
    w.u4(m.msss_ms);
  });
}

bool decode(std::span<const std::uint8_t> p, NavStatus& m) {
  if (p.size() < NavStatus::kPayloadSize) return false;
  const Reader r(p);
  m.i_tow_ms = r.u4(0);
  m.gps_fix = r.u1(4);
  m.flags = r.u1(5);
  m.fix_stat = r.u1(6);
  m.flags2 = r.u1(7);
  m.ttff_ms = r.u4(8);
  m.msss_ms = r.u4(12);
  return r.ok();
}

// UBX-NAV-SOL payload (u-blox 8).
void append(const NavSol& m, std::vector<std::uint8_t>& out) {
  frame(NavSol::kMsg, out, [&](Writer& w) {
    w.u4(m.i_tow_ms);
    w.i4(m.f_tow_ns);
    w.i2(m.week);
    w.u1(m.gps_fix);
    w.u1(m.flags);
    w.i4(m.ecef_x_cm);
    w.i4(m.ecef_y_cm);
    w.i4(m.ecef_z_cm);
    w.u4(m.p_acc_cm);
    w.i4(m.ecef_vx_cmps);
    w.i4(m.ecef_vy_cmps);
    w.i4(m.ecef_vz_cmps);
    w.u4(m.s_acc_cmps);
    w.u2(m.p_dop_0p01);
    w.u1(m.reserved1);
    w.u1(m.num_sv);
    put_bytes(w, m.reserved2);
  });
}

bool decode(std::span<const std::uint8_t> p, NavSol& m) {
  if (p.size() < NavSol::kPayloadSize) return false;
  const Reader r(p);
  m.i_tow_ms = r.u4(0);
  m.f_tow_ns = r.i4(4);
  m.week = r.i2(8);
  m.gps_fix = r.u1(10);
  m.flags = r.u1(11);
  m.ecef_x_cm = r.i4(12);
  m.ecef_y_cm = r.i4(16);
  m.ecef_z_cm = r.i4(20);
  m.p_acc_cm = r.u4(24);
  m.ecef_vx_cmps = r.i4(28);
  m.ecef_vy_cmps = r.i4(32);
  m.ecef_vz_cmps = r.i4(36);
  m.s_acc_cmps = r.u4(40);
  m.p_dop_0p01 = r.u2(44);
  m.reserved1 = r.u1(46);
  m.num_sv = r.u1(47);
  get_bytes(r, 48, m.reserved2);
  return r.ok();
}

// UBX-NAV-SVINFO payload (u-blox 8): header, then numCh blocks of 12 bytes.
void append(const NavSvinfo& m, std::vector<std::uint8_t>& out) {
  const std::size_t n = block_count(m.channels.size());
  frame(NavSvinfo::kMsg, out, [&](Writer& w) {
    w.u4(m.i_tow_ms);
    w.u1(static_cast<std::uint8_t>(n));
    w.u1(m.global_flags);
    put_bytes(w, m.reserved1);
    for (std::size_t i = 0; i < n; ++i) {
      const NavSvinfoChannel& c = m.channels[i];
      w.u1(c.chn);
      w.u1(c.svid);
      w.u1(c.flags);
      w.u1(c.quality);
      w.u1(c.cno_dbhz);
      w.i1(c.elev_deg);
      w.i2(c.azim_deg);
      w.i4(c.pr_res_cm);
    }
  });
}

bool decode(std::span<const std::uint8_t> p, NavSvinfo& m) {
  if (!blocks_fit(p, NavSvinfo::kHeaderSize, NavSvinfo::kBlockSize, 4)) return false;
  const Reader r(p);
  m.i_tow_ms = r.u4(0);
  const std::size_t n = r.u1(4);
  m.global_flags = r.u1(5);
  get_bytes(r, 6, m.reserved1);
  m.channels.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t o = NavSvinfo::kHeaderSize + NavSvinfo::kBlockSize * i;
    NavSvinfoChannel& c = m.channels[i];
    c.chn = r.u1(o);
    c.svid = r.u1(o + 1);
    c.flags = r.u1(o + 2);
    c.quality = r.u1(o + 3);
    c.cno_dbhz = r.u1(o + 4);
    c.elev_deg = r.i1(o + 5);
    c.azim_deg = r.i2(o + 6);
    c.pr_res_cm = r.i4(o + 8);
  }
  return r.ok();
}

// UBX-NAV-DOP payload.
void append(const NavDop& m, std::vector<std::uint8_t>& out) {
  frame(NavDop::kMsg, out, [&](Writer& w) {
    w.u4(m.i_tow_ms);
    w.u2(m.g_dop_0p01);
    w.u2(m.p_dop_0p01);
    w.u2(m.t_dop_0p01);
    w.u2(m.v_dop_0p01);
    w.u2(m.h_dop_0p01);
    w.u2(m.n_dop_0p01);
    w.u2(m.e_dop_0p01);
  });
}

bool decode(std::span<const std::uint8_t> p, NavDop& m) {
  if (p.size() < NavDop::kPayloadSize) return false;
  const Reader r(p);
  m.i_tow_ms = r.u4(0);
  m.g_dop_0p01 = r.u2(4);
  m.p_dop_0p01 = r.u2(6);
  m.t_dop_0p01 = r.u2(8);
  m.v_dop_0p01 = r.u2(10);
  m.h_dop_0p01 = r.u2(12);
  m.n_dop_0p01 = r.u2(14);
  m.e_dop_0p01 = r.u2(16);
  return r.ok();
}

// UBX-NAV-SAT payload: header, then numSvs blocks of 12 bytes.
void append(const NavSat& m, std::vector<std::uint8_t>& out) {
  const std::size_t n = block_count(m.svs.size());
  frame(NavSat::kMsg, out, [&](Writer& w) {
    w.u4(m.i_tow_ms);
    w.u1(m.version);
    w.u1(static_cast<std::uint8_t>(n));
    put_bytes(w, m.reserved1);
    for (std::size_t i = 0; i < n; ++i) {
      const NavSatSv& s = m.svs[i];
      w.u1(s.gnss_id);
      w.u1(s.sv_id);
      w.u1(s.cno_dbhz);
      w.i1(s.elev_deg);
      w.i2(s.azim_deg);
      w.i2(s.pr_res_dm);
      w.u4(s.flags);
    }
  });
}

bool decode(std::span<const std::uint8_t> p, NavSat& m) {
  if (!blocks_fit(p, NavSat::kHeaderSize, NavSat::kBlockSize, 5)) return false;
  const Reader r(p);
  m.i_tow_ms = r.u4(0);
  m.version = r.u1(4);
  const std::size_t n = r.u1(5);
  get_bytes(r, 6, m.reserved1);
  m.svs.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t o = NavSat::kHeaderSize + NavSat::kBlockSize * i;
    NavSatSv& s = m.svs[i];
    s.gnss_id = r.u1(o);
    s.sv_id = r.u1(o + 1);
    s.cno_dbhz = r.u1(o + 2);
    s.elev_deg = r.i1(o + 3);
    s.azim_deg = r.i2(o + 4);
    s.pr_res_dm = r.i2(o + 6);
    s.flags = r.u4(o + 8);
  }
  return r.ok();
}

// UBX-NAV-TIMEGPS payload.
void append(const NavTimegps& m, std::vector<std::uint8_t>& out) {
  frame(NavTimegps::kMsg, out, [&](Writer& w) {
    w.u4(m.i_tow_ms);
    w.i4(m.f_tow_ns);
    w.i2(m.week);
    w.i1(m.leap_s);
    w.u1(m.valid);
    w.u4(m.t_acc_ns);
  });
}

bool decode(std::span<const std::uint8_t> p, NavTimegps& m) {
  if (p.size() < NavTimegps::kPayloadSize) return false;
  const Reader r(p);
  m.i_tow_ms = r.u4(0);
  m.f_tow_ns = r.i4(4);
  m.week = r.i2(8);
  m.leap_s = r.i1(10);
  m.valid = r.u1(11);
  m.t_acc_ns = r.u4(12);
  return r.ok();
}

// UBX-NAV-TIMEUTC payload.
void append(const NavTimeutc& m, std::vector<std::uint8_t>& out) {
  frame(NavTimeutc::kMsg, out, [&](Writer& w) {
    w.u4(m.i_tow_ms);
    w.u4(m.t_acc_ns);
    w.i4(m.nano_ns);
    w.u2(m.year);
    w.u1(m.month);
    w.u1(m.day);
    w.u1(m.hour);
    w.u1(m.min);
    w.u1(m.sec);
    w.u1(m.valid);
  });
}

bool decode(std::span<const std::uint8_t> p, NavTimeutc& m) {
  if (p.size() < NavTimeutc::kPayloadSize) return false;
  const Reader r(p);
  m.i_tow_ms = r.u4(0);
  m.t_acc_ns = r.u4(4);
  m.nano_ns = r.i4(8);
  m.year = r.u2(12);
  m.month = r.u1(14);
  m.day = r.u1(15);
  m.hour = r.u1(16);
  m.min = r.u1(17);
  m.sec = r.u1(18);
  m.valid = r.u1(19);
  return r.ok();
}

// UBX-NAV-CLOCK payload.
void append(const NavClock& m, std::vector<std::uint8_t>& out) {
  frame(NavClock::kMsg, out, [&](Writer& w) {
    w.u4(m.i_tow_ms);
    w.i4(m.clk_b_ns);
    w.i4(m.clk_d_nsps);
    w.u4(m.t_acc_ns);
    w.u4(m.f_acc_psps);
  });
}

bool decode(std::span<const std::uint8_t> p, NavClock& m) {
  if (p.size() < NavClock::kPayloadSize) return false;
  const Reader r(p);
  m.i_tow_ms = r.u4(0);
  m.clk_b_ns = r.i4(4);
  m.clk_d_nsps = r.i4(8);
  m.t_acc_ns = r.u4(12);
  m.f_acc_psps = r.u4(16);
  return r.ok();
}

// UBX-NAV-EOE payload.
void append(const NavEoe& m, std::vector<std::uint8_t>& out) {
  frame(NavEoe::kMsg, out, [&](Writer& w) { w.u4(m.i_tow_ms); });
}

bool decode(std::span<const std::uint8_t> p, NavEoe& m) {
  if (p.size() < NavEoe::kPayloadSize) return false;
  m.i_tow_ms = Reader(p).u4(0);
  return true;
}

// ---- RXM -----------------------------------------------------------------------------------

// UBX-RXM-RAWX payload: 16-byte header, then numMeas blocks of 32 bytes.
void append(const RxmRawx& m, std::vector<std::uint8_t>& out) {
  const std::size_t n = block_count(m.meas.size());
  frame(RxmRawx::kMsg, out, [&](Writer& w) {
    w.r8(m.rcv_tow_s);
    w.u2(m.week);
    w.i1(m.leap_s);
    w.u1(static_cast<std::uint8_t>(n));
    w.u1(m.rec_stat);
    w.u1(m.version);
    put_bytes(w, m.reserved1);
    for (std::size_t i = 0; i < n; ++i) {
      const RxmRawxMeas& s = m.meas[i];
      w.r8(s.pr_mes_m);
      w.r8(s.cp_mes_cycles);
      w.r4(s.do_mes_hz);
      w.u1(s.gnss_id);
      w.u1(s.sv_id);
      w.u1(s.sig_id);
      w.u1(s.freq_id);
      w.u2(s.locktime_ms);
      w.u1(s.cno_dbhz);
      w.u1(s.pr_stdev);
      w.u1(s.cp_stdev);
      w.u1(s.do_stdev);
      w.u1(s.trk_stat);
      w.u1(s.reserved3);
    }
  });
}

bool decode(std::span<const std::uint8_t> p, RxmRawx& m) {
  if (!blocks_fit(p, RxmRawx::kHeaderSize, RxmRawx::kBlockSize, 11)) return false;
  const Reader r(p);
  m.rcv_tow_s = r.r8(0);
  m.week = r.u2(8);
  m.leap_s = r.i1(10);
  const std::size_t n = r.u1(11);
  m.rec_stat = r.u1(12);
  m.version = r.u1(13);
  get_bytes(r, 14, m.reserved1);
  m.meas.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t o = RxmRawx::kHeaderSize + RxmRawx::kBlockSize * i;
    RxmRawxMeas& s = m.meas[i];
    s.pr_mes_m = r.r8(o);
    s.cp_mes_cycles = r.r8(o + 8);
    s.do_mes_hz = r.r4(o + 16);
    s.gnss_id = r.u1(o + 20);
    s.sv_id = r.u1(o + 21);
    s.sig_id = r.u1(o + 22);
    s.freq_id = r.u1(o + 23);
    s.locktime_ms = r.u2(o + 24);
    s.cno_dbhz = r.u1(o + 26);
    s.pr_stdev = r.u1(o + 27);
    s.cp_stdev = r.u1(o + 28);
    s.do_stdev = r.u1(o + 29);
    s.trk_stat = r.u1(o + 30);
    s.reserved3 = r.u1(o + 31);
  }
  return r.ok();
}

// UBX-RXM-SFRBX payload: 8-byte header, then numWords U4 words.
void append(const RxmSfrbx& m, std::vector<std::uint8_t>& out) {
  const std::size_t n = block_count(m.words.size());
  frame(RxmSfrbx::kMsg, out, [&](Writer& w) {
    w.u1(m.gnss_id);
    w.u1(m.sv_id);
    w.u1(m.sig_id);
    w.u1(m.freq_id);
    w.u1(static_cast<std::uint8_t>(n));
    w.u1(m.chn);
    w.u1(m.version);
    w.u1(m.reserved2);
    for (std::size_t i = 0; i < n; ++i) w.u4(m.words[i]);
  });
}

bool decode(std::span<const std::uint8_t> p, RxmSfrbx& m) {
  if (!blocks_fit(p, RxmSfrbx::kHeaderSize, 4, 4)) return false;
  const Reader r(p);
  m.gnss_id = r.u1(0);
  m.sv_id = r.u1(1);
  m.sig_id = r.u1(2);
  m.freq_id = r.u1(3);
  const std::size_t n = r.u1(4);
  m.chn = r.u1(5);
  m.version = r.u1(6);
  m.reserved2 = r.u1(7);
  m.words.resize(n);
  for (std::size_t i = 0; i < n; ++i) m.words[i] = r.u4(RxmSfrbx::kHeaderSize + 4 * i);
  return r.ok();
}

// ---- ACK -----------------------------------------------------------------------------------

void append(const AckAck& m, std::vector<std::uint8_t>& out) {
  frame(AckAck::kMsg, out, [&](Writer& w) {
    w.u1(m.cls_id);
    w.u1(m.msg_id);
  });
}

bool decode(std::span<const std::uint8_t> p, AckAck& m) {
  if (p.size() != AckAck::kPayloadSize) return false;
  m.cls_id = p[0];
  m.msg_id = p[1];
  return true;
}

void append(const AckNak& m, std::vector<std::uint8_t>& out) {
  frame(AckNak::kMsg, out, [&](Writer& w) {
    w.u1(m.cls_id);
    w.u1(m.msg_id);
  });
}

bool decode(std::span<const std::uint8_t> p, AckNak& m) {
  if (p.size() != AckNak::kPayloadSize) return false;
  m.cls_id = p[0];
  m.msg_id = p[1];
  return true;
}

// ---- MON -----------------------------------------------------------------------------------

// UBX-MON-VER payload: swVersion CH[30], hwVersion CH[10], then extension CH[30] repeated.
void append(const MonVer& m, std::vector<std::uint8_t>& out) {
  // The 16-bit length caps the number of extensions.
  const std::size_t max_ext =
      (kMaxWirePayload - MonVer::kSwSize - MonVer::kHwSize) / MonVer::kExtensionSize;
  const std::size_t n = std::min(m.extensions.size(), max_ext);
  frame(MonVer::kMsg, out, [&](Writer& w) {
    put_string(w, m.sw_version, MonVer::kSwSize);
    put_string(w, m.hw_version, MonVer::kHwSize);
    for (std::size_t i = 0; i < n; ++i) put_string(w, m.extensions[i], MonVer::kExtensionSize);
  });
}

bool decode(std::span<const std::uint8_t> p, MonVer& m) {
  constexpr std::size_t kHeader = MonVer::kSwSize + MonVer::kHwSize;
  if (p.size() < kHeader || (p.size() - kHeader) % MonVer::kExtensionSize != 0) return false;
  m.sw_version = get_string(p, 0, MonVer::kSwSize);
  m.hw_version = get_string(p, MonVer::kSwSize, MonVer::kHwSize);
  const std::size_t n = (p.size() - kHeader) / MonVer::kExtensionSize;
  m.extensions.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    m.extensions[i] = get_string(p, kHeader + MonVer::kExtensionSize * i, MonVer::kExtensionSize);
  return true;
}

int protocol_version_x100(const MonVer& m) {
  for (const std::string& e : m.extensions) {
    if (e.rfind("PROTVER", 0) != 0 || e.size() < 9 || (e[7] != '=' && e[7] != ' ')) continue;
    // "PROTVER=xx.yy": integer part, optional fraction of up to two digits.
    const char* first = e.data() + 8;
    const char* last = e.data() + e.size();
    int major = 0;
    auto [p, ec] = std::from_chars(first, last, major);
    if (ec != std::errc() || major < 0) return 0;
    int minor = 0;
    if (p != last && *p == '.') {
      ++p;
      int digits = 0;
      while (p != last && *p >= '0' && *p <= '9' && digits < 2) {
        minor = minor * 10 + (*p - '0');
        ++p;
        ++digits;
      }
      if (digits == 1) minor *= 10;
    }
    return major * 100 + minor;
  }
  return 0;
}

// UBX-MON-HW payload (u-blox 8).
void append(const MonHw& m, std::vector<std::uint8_t>& out) {
  frame(MonHw::kMsg, out, [&](Writer& w) {
    w.u4(m.pin_sel);
    w.u4(m.pin_bank);
    w.u4(m.pin_dir);
    w.u4(m.pin_val);
    w.u2(m.noise_per_ms);
    w.u2(m.agc_cnt);
    w.u1(m.a_status);
    w.u1(m.a_power);
    w.u1(m.flags);
    w.u1(m.reserved1);
    w.u4(m.used_mask);
    put_bytes(w, m.vp);
    w.u1(m.jam_ind);
    put_bytes(w, m.reserved2);
    w.u4(m.pin_irq);
    w.u4(m.pull_h);
    w.u4(m.pull_l);
  });
}

bool decode(std::span<const std::uint8_t> p, MonHw& m) {
  if (p.size() != MonHw::kPayloadSize) return false;
  const Reader r(p);
  m.pin_sel = r.u4(0);
  m.pin_bank = r.u4(4);
  m.pin_dir = r.u4(8);
  m.pin_val = r.u4(12);
  m.noise_per_ms = r.u2(16);
  m.agc_cnt = r.u2(18);
  m.a_status = r.u1(20);
  m.a_power = r.u1(21);
  m.flags = r.u1(22);
  m.reserved1 = r.u1(23);
  m.used_mask = r.u4(24);
  get_bytes(r, 28, m.vp);
  m.jam_ind = r.u1(45);
  get_bytes(r, 46, m.reserved2);
  m.pin_irq = r.u4(48);
  m.pull_h = r.u4(52);
  m.pull_l = r.u4(56);
  return r.ok();
}

// ---- CFG -----------------------------------------------------------------------------------

// UBX-CFG-PRT poll: no payload, or the port ID.
void append(const CfgPrtPoll& m, std::vector<std::uint8_t>& out) {
  frame(CfgPrtPoll::kMsg, out, [&](Writer& w) {
    if (m.has_port_id) w.u1(m.port_id);
  });
}

bool decode(std::span<const std::uint8_t> p, CfgPrtPoll& m) {
  if (p.size() > 1) return false;
  m.has_port_id = p.size() == 1;
  m.port_id = m.has_port_id ? p[0] : 0;
  return true;
}

// UBX-CFG-PRT payload (UART layout; other ports use the same offsets).
void append(const CfgPrt& m, std::vector<std::uint8_t>& out) {
  frame(CfgPrt::kMsg, out, [&](Writer& w) {
    w.u1(m.port_id);
    w.u1(m.reserved1);
    w.u2(m.tx_ready);
    w.u4(m.mode);
    w.u4(m.baud_rate);
    w.u2(m.in_proto_mask);
    w.u2(m.out_proto_mask);
    w.u2(m.flags);
    put_bytes(w, m.reserved2);
  });
}

bool decode(std::span<const std::uint8_t> p, CfgPrt& m) {
  if (p.size() != CfgPrt::kPayloadSize) return false;
  const Reader r(p);
  m.port_id = r.u1(0);
  m.reserved1 = r.u1(1);
  m.tx_ready = r.u2(2);
  m.mode = r.u4(4);
  m.baud_rate = r.u4(8);
  m.in_proto_mask = r.u2(12);
  m.out_proto_mask = r.u2(14);
  m.flags = r.u2(16);
  get_bytes(r, 18, m.reserved2);
  return r.ok();
}

// UBX-CFG-MSG, the three forms.
void append(const CfgMsgPoll& m, std::vector<std::uint8_t>& out) {
  frame(CfgMsgPoll::kMsg, out, [&](Writer& w) {
    w.u1(m.msg_class);
    w.u1(m.msg_id);
  });
}

bool decode(std::span<const std::uint8_t> p, CfgMsgPoll& m) {
  if (p.size() != CfgMsgPoll::kPayloadSize) return false;
  m.msg_class = p[0];
  m.msg_id = p[1];
  return true;
}

void append(const CfgMsgCurrentPort& m, std::vector<std::uint8_t>& out) {
  frame(CfgMsgCurrentPort::kMsg, out, [&](Writer& w) {
    w.u1(m.msg_class);
    w.u1(m.msg_id);
    w.u1(m.rate);
  });
}

bool decode(std::span<const std::uint8_t> p, CfgMsgCurrentPort& m) {
  if (p.size() != CfgMsgCurrentPort::kPayloadSize) return false;
  m.msg_class = p[0];
  m.msg_id = p[1];
  m.rate = p[2];
  return true;
}

void append(const CfgMsg& m, std::vector<std::uint8_t>& out) {
  frame(CfgMsg::kMsg, out, [&](Writer& w) {
    w.u1(m.msg_class);
    w.u1(m.msg_id);
    put_bytes(w, m.rate);
  });
}

bool decode(std::span<const std::uint8_t> p, CfgMsg& m) {
  if (p.size() != CfgMsg::kPayloadSize) return false;
  const Reader r(p);
  m.msg_class = r.u1(0);
  m.msg_id = r.u1(1);
  get_bytes(r, 2, m.rate);
  return r.ok();
}

// UBX-CFG-RATE payload.
void append(const CfgRate& m, std::vector<std::uint8_t>& out) {
  frame(CfgRate::kMsg, out, [&](Writer& w) {
    w.u2(m.meas_rate_ms);
    w.u2(m.nav_rate_cycles);
    w.u2(m.time_ref);
  });
}

bool decode(std::span<const std::uint8_t> p, CfgRate& m) {
  if (p.size() != CfgRate::kPayloadSize) return false;
  const Reader r(p);
  m.meas_rate_ms = r.u2(0);
  m.nav_rate_cycles = r.u2(2);
  m.time_ref = r.u2(4);
  return r.ok();
}

// UBX-CFG-NAV5 payload.
void append(const CfgNav5& m, std::vector<std::uint8_t>& out) {
  frame(CfgNav5::kMsg, out, [&](Writer& w) {
    w.u2(m.mask);
    w.u1(m.dyn_model);
    w.u1(m.fix_mode);
    w.i4(m.fixed_alt_cm);
    w.u4(m.fixed_alt_var_1e4m2);
    w.i1(m.min_elev_deg);
    w.u1(m.dr_limit_s);
    w.u2(m.p_dop_0p1);
    w.u2(m.t_dop_0p1);
    w.u2(m.p_acc_m);
    w.u2(m.t_acc_m);
    w.u1(m.static_hold_thresh_cmps);
    w.u1(m.dgnss_timeout_s);
    w.u1(m.cno_thresh_num_svs);
    w.u1(m.cno_thresh_dbhz);
    put_bytes(w, m.reserved1);
    w.u2(m.static_hold_max_dist_m);
    w.u1(m.utc_standard);
    put_bytes(w, m.reserved2);
  });
}

bool decode(std::span<const std::uint8_t> p, CfgNav5& m) {
  if (p.size() != CfgNav5::kPayloadSize) return false;
  const Reader r(p);
  m.mask = r.u2(0);
  m.dyn_model = r.u1(2);
  m.fix_mode = r.u1(3);
  m.fixed_alt_cm = r.i4(4);
  m.fixed_alt_var_1e4m2 = r.u4(8);
  m.min_elev_deg = r.i1(12);
  m.dr_limit_s = r.u1(13);
  m.p_dop_0p1 = r.u2(14);
  m.t_dop_0p1 = r.u2(16);
  m.p_acc_m = r.u2(18);
  m.t_acc_m = r.u2(20);
  m.static_hold_thresh_cmps = r.u1(22);
  m.dgnss_timeout_s = r.u1(23);
  m.cno_thresh_num_svs = r.u1(24);
  m.cno_thresh_dbhz = r.u1(25);
  get_bytes(r, 26, m.reserved1);
  m.static_hold_max_dist_m = r.u2(28);
  m.utc_standard = r.u1(30);
  get_bytes(r, 31, m.reserved2);
  return r.ok();
}

// UBX-CFG-GNSS payload: 4-byte header, then numConfigBlocks blocks of 8 bytes.
void append(const CfgGnss& m, std::vector<std::uint8_t>& out) {
  const std::size_t n = block_count(m.blocks.size());
  frame(CfgGnss::kMsg, out, [&](Writer& w) {
    w.u1(m.msg_ver);
    w.u1(m.num_trk_ch_hw);
    w.u1(m.num_trk_ch_use);
    w.u1(static_cast<std::uint8_t>(n));
    for (std::size_t i = 0; i < n; ++i) {
      const CfgGnssBlock& b = m.blocks[i];
      w.u1(b.gnss_id);
      w.u1(b.res_trk_ch);
      w.u1(b.max_trk_ch);
      w.u1(b.reserved1);
      w.u4(b.flags);
    }
  });
}

bool decode(std::span<const std::uint8_t> p, CfgGnss& m) {
  if (!blocks_fit(p, CfgGnss::kHeaderSize, CfgGnss::kBlockSize, 3)) return false;
  const Reader r(p);
  m.msg_ver = r.u1(0);
  m.num_trk_ch_hw = r.u1(1);
  m.num_trk_ch_use = r.u1(2);
  const std::size_t n = r.u1(3);
  m.blocks.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t o = CfgGnss::kHeaderSize + CfgGnss::kBlockSize * i;
    CfgGnssBlock& b = m.blocks[i];
    b.gnss_id = r.u1(o);
    b.res_trk_ch = r.u1(o + 1);
    b.max_trk_ch = r.u1(o + 2);
    b.reserved1 = r.u1(o + 3);
    b.flags = r.u4(o + 4);
  }
  return r.ok();
}

// UBX-CFG-CFG payload: three masks and the optional device mask.
void append(const CfgCfg& m, std::vector<std::uint8_t>& out) {
  frame(CfgCfg::kMsg, out, [&](Writer& w) {
    w.u4(m.clear_mask);
    w.u4(m.save_mask);
    w.u4(m.load_mask);
    if (m.has_device_mask) w.u1(m.device_mask);
  });
}

bool decode(std::span<const std::uint8_t> p, CfgCfg& m) {
  if (p.size() != 12 && p.size() != 13) return false;
  const Reader r(p);
  m.clear_mask = r.u4(0);
  m.save_mask = r.u4(4);
  m.load_mask = r.u4(8);
  m.has_device_mask = p.size() == 13;
  m.device_mask = m.has_device_mask ? p[12] : 0;
  return r.ok();
}

// UBX-CFG-RST payload.
void append(const CfgRst& m, std::vector<std::uint8_t>& out) {
  frame(CfgRst::kMsg, out, [&](Writer& w) {
    w.u2(m.nav_bbr_mask);
    w.u1(m.reset_mode);
    w.u1(m.reserved1);
  });
}

bool decode(std::span<const std::uint8_t> p, CfgRst& m) {
  if (p.size() != CfgRst::kPayloadSize) return false;
  const Reader r(p);
  m.nav_bbr_mask = r.u2(0);
  m.reset_mode = r.u1(2);
  m.reserved1 = r.u1(3);
  return r.ok();
}

// UBX-CFG-VALGET request (version 0) and answer (version 1) (UBX-18010854 section 5, CFG-VALGET).
void append(const CfgValgetRequest& m, std::vector<std::uint8_t>& out) {
  frame(CfgValgetRequest::kMsg, out, [&](Writer& w) {
    w.u1(m.version);
    w.u1(m.layer);
    w.u2(m.position);
    put_keys(w, m.keys);
  });
}

bool decode(std::span<const std::uint8_t> p, CfgValgetRequest& m) {
  if (p.size() < 4 || p[0] != 0) return false;
  const Reader r(p);
  m.version = r.u1(0);
  m.layer = r.u1(1);
  m.position = r.u2(2);
  return get_keys(p, 4, m.keys);
}

void append(const CfgValgetResponse& m, std::vector<std::uint8_t>& out) {
  frame(CfgValgetResponse::kMsg, out, [&](Writer& w) {
    w.u1(m.version);
    w.u1(m.layer);
    w.u2(m.position);
    put_key_values(w, m.values);
  });
}

bool decode(std::span<const std::uint8_t> p, CfgValgetResponse& m) {
  if (p.size() < 4 || p[0] != 1) return false;
  const Reader r(p);
  m.version = r.u1(0);
  m.layer = r.u1(1);
  m.position = r.u2(2);
  return get_key_values(p, 4, m.values);
}

// UBX-CFG-VALSET: version, layers, transaction (version 1; reserved in version 0), reserved.
void append(const CfgValset& m, std::vector<std::uint8_t>& out) {
  frame(CfgValset::kMsg, out, [&](Writer& w) {
    w.u1(m.version);
    w.u1(m.layers);
    w.u1(m.transaction);
    w.u1(m.reserved0);
    put_key_values(w, m.values);
  });
}

bool decode(std::span<const std::uint8_t> p, CfgValset& m) {
  if (p.size() < 4 || p[0] > 1) return false;
  m.version = p[0];
  m.layers = p[1];
  m.transaction = p[2];
  m.reserved0 = p[3];
  return get_key_values(p, 4, m.values);
}

// UBX-CFG-VALDEL: as VALSET with keys only.
void append(const CfgValdel& m, std::vector<std::uint8_t>& out) {
  frame(CfgValdel::kMsg, out, [&](Writer& w) {
    w.u1(m.version);
    w.u1(m.layers);
    w.u1(m.transaction);
    w.u1(m.reserved0);
    put_keys(w, m.keys);
  });
}

bool decode(std::span<const std::uint8_t> p, CfgValdel& m) {
  if (p.size() < 4 || p[0] > 1) return false;
  m.version = p[0];
  m.layers = p[1];
  m.transaction = p[2];
  m.reserved0 = p[3];
  return get_keys(p, 4, m.keys);
}

}  // namespace navemu::ubx
