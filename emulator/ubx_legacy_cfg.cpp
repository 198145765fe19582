#include "emulator/ubx_legacy_cfg.hpp"

#include <algorithm>
#include <string_view>

#include "protocols/ubx.hpp"

namespace navemu {

using namespace ubx;

namespace {

using Bytes = std::vector<std::uint8_t>;
using Payload = std::span<const std::uint8_t>;

template <class T>
bool decodes(Payload p) {
  T m;
  return decode(p, m);
}

template <class T>
Bytes encoded(const T& m) {
  Bytes out;
  append(m, out);
  // append() writes the whole frame: sync, class, ID, length, payload, checksum.
  return Bytes(out.begin() + 6, out.end() - 2);
}

// Power-up values (UBX-13003221 32.10 and the F9 descriptions' defaults) where they are
// established; otherwise the message's zero form, which a set replaces.
Bytes power_up(MsgId id, std::uint8_t index, bool protocol27) {
  if (id == kCfgInf) {
    // INF messages ERROR, WARNING and NOTICE go out as NMEA TXT on every port but UART2 (the
    // parts' $GxTXT at start-up); none as UBX INF.
    CfgInf m;
    CfgInfBlock b;
    b.protocol_id = index;
    if (index == 1)
      for (std::uint8_t port : kPortsButUart2) b.inf_msg_mask[port] = 0x07;
    m.blocks = {b};
    return encoded(m);
  }
  if (id == kCfgTp5) {
    // TIMEPULSE: 1 Hz, 100 ms long once locked, aligned to the top of the second, rising edge,
    // 50 ns antenna cable delay; TIMEPULSE2 off (CFG-TP-* defaults).
    CfgTp5 m;
    m.tp_idx = index;
    m.version = 1;
    if (index == 0) {
      m.ant_cable_delay_ns = 50;
      m.freq_period_hz_or_us = m.freq_period_lock_hz_or_us = 1'000'000;
      m.pulse_len_ratio_lock_us_or_2m32 = 100'000;
      m.flags = 0x77;  // active, lockGnssFreq, lockedOtherSet, isLength, alignToTow, polarity
    }
    return encoded(m);
  }
  if (id == kCfgSbas) return encoded(CfgSbas{1, 3, 3, 0, 0});
  if (id == kCfgGnss) return encoded(m8_power_up_gnss());  // on, ranging + corrections, 3 SBAS
  if (id == kCfgNmea) {
    CfgNmea m;
    m.nmea_version = 0x40;
    m.has_v0 = m.has_v1 = true;
    m.version = 1;
    return encoded(m);
  }
  if (id == kCfgRinv) {
    CfgRinv m;
    const std::string_view text = "Notice: no data saved!";
    m.data.assign(text.begin(), text.end());
    return encoded(m);
  }
  if (id == kCfgUsb) {
    CfgUsb m;
    m.vendor_id = 0x1546;  // u-blox AG
    m.product_id = protocol27 ? 0x01A9 : 0x01A8;
    m.vendor_string = "u-blox AG - www.u-blox.com";
    m.product_string = "u-blox GNSS receiver";
    return encoded(m);
  }
  if (id == kCfgDat) {
    CfgDatCurrent m;
    m.datum_name = "WGS84";
    return encoded(m);
  }
  if (id == kCfgNavx5) return encoded(CfgNavx5{});
  if (id == kCfgItfm) return encoded(CfgItfm{});
  if (id == kCfgDgnss) return encoded(CfgDgnss{});
  if (id == kCfgOdo) return encoded(CfgOdo{});
  if (id == kCfgAnt) return encoded(CfgAnt{});
  if (id == kCfgPm2) return encoded(CfgPm2{});
  if (id == kCfgRxm) return encoded(CfgRxm{});
  if (id == kCfgPms) return encoded(CfgPms{});
  if (id == kCfgGeofence) return encoded(CfgGeofence{});
  if (id == kCfgLogfilter) return encoded(CfgLogfilter{});
  return {};
}

}  // namespace

namespace {

// The messages, which parts have them (UBX-13003221 32.10 for the u-blox 8 standard-precision
// part; the F9 HPG interface descriptions for the F9P: no power-save, SBAS or RXM messages,
// and CFG-INF, ITFM, NMEA, ODO, TMODE3 and TP5 are views of its configuration items,
// emulator/ubx_device.cpp), whether a shorter set form extends into the longer one (CFG-NMEA
// 4/12/20 bytes, CFG-NAVX5 40/44, CFG-PM2 44/48), whether they can be polled, and how a set is
// checked.
constexpr struct {
  MsgId id;
  bool m8, f9, extends, pollable;
  bool (*valid)(Payload);
} kEntries[] = {
    {kCfgInf, true, false, false, true, &decodes<CfgInf>},
    {kCfgDat, true, true, false, true, &decodes<CfgDat>},
    {kCfgRxm, true, false, false, true, &decodes<CfgRxm>},
    {kCfgAnt, true, true, false, true, &decodes<CfgAnt>},
    {kCfgSbas, true, false, false, true, &decodes<CfgSbas>},
    {kCfgNmea, true, false, true, true, &decodes<CfgNmea>},
    {kCfgUsb, true, true, false, true, &decodes<CfgUsb>},
    {kCfgOdo, true, false, false, true, &decodes<CfgOdo>},
    {kCfgNavx5, true, true, true, true, &decodes<CfgNavx5>},
    {kCfgTp5, true, false, false, true, &decodes<CfgTp5>},
    {kCfgRinv, true, true, false, true, &decodes<CfgRinv>},
    {kCfgItfm, true, false, false, true, &decodes<CfgItfm>},
    {kCfgPm2, true, false, true, true, &decodes<CfgPm2>},
    {kCfgLogfilter, true, true, false, true, &decodes<CfgLogfilter>},
    {kCfgPwr, true, true, false, false, &decodes<CfgPwr>},
    {kCfgGeofence, true, true, false, true, &decodes<CfgGeofence>},
    {kCfgDgnss, false, true, false, true, &decodes<CfgDgnss>},
    {kCfgPms, true, false, false, true, &decodes<CfgPms>},
    {kCfgGnss, true, false, false, true, &decodes<CfgGnss>},
};

constexpr std::uint16_t key_of(MsgId id) { return static_cast<std::uint16_t>(id.cls << 8 | id.id); }

}  // namespace

CfgGnss m8_power_up_gnss() {
  CfgGnss g;
  g.num_trk_ch_hw = g.num_trk_ch_use = 32;
  const auto block = [](std::uint8_t id, std::uint8_t res, std::uint8_t max, bool on) {
    return CfgGnssBlock{id, res, max, 0, (on ? CfgGnssBlock::kEnable : 0u) | (1u << CfgGnssBlock::kSigCfgMaskShift)};
  };
  g.blocks = {block(0, 8, 16, true), block(1, 1, 3, true),  block(2, 4, 8, false), block(3, 8, 16, false),
              block(4, 0, 8, false), block(5, 0, 3, true), block(6, 8, 14, true)};
  return g;
}

UbxLegacyCfg::UbxLegacyCfg(bool protocol27) : protocol27_(protocol27) {}

bool UbxLegacyCfg::has(MsgId id) const {
  return std::any_of(std::begin(kEntries), std::end(kEntries),
                     [&](const auto& e) { return e.id == id && (protocol27_ ? e.f9 : e.m8); });
}

Bytes UbxLegacyCfg::current(MsgId id, std::uint8_t index) const {
  const auto it = ram_.find({key_of(id), index});
  return it != ram_.end() ? it->second : power_up(id, index, protocol27_);
}

bool UbxLegacyCfg::handle(MsgId id, Payload p, Bytes& out) {
  const auto* e = std::find_if(std::begin(kEntries), std::end(kEntries), [&](const auto& x) { return x.id == id; });
  if (e == std::end(kEntries) || !(protocol27_ ? e->f9 : e->m8)) return false;
  // The poll forms: empty, or one index byte (CFG-INF protocol 0 UBX / 1 NMEA; CFG-TP5 time
  // pulse 0 / 1). CFG-INF has no empty poll.
  const bool indexed = id == kCfgInf || id == kCfgTp5;
  const bool poll = e->pollable && (indexed ? p.size() <= 1 && !(id == kCfgInf && p.empty()) : p.empty());
  if (poll) {
    const std::uint8_t index = p.empty() ? 0 : p[0];
    if (indexed && index > 1) return false;
    append_frame(id.cls, id.id, current(id, index), out);
    return true;
  }
  if (!e->valid(p)) return false;
  if (id == kCfgPwr) return true;  // a command: the power state is not modelled
  if (id == kCfgInf) {  // one block per protocol, each kept on its own
    CfgInf m;
    decode(p, m);
    for (const CfgInfBlock& b : m.blocks) {
      CfgInf one;
      one.blocks = {b};
      ram_[{key_of(id), b.protocol_id}] = encoded(one);
    }
    return true;
  }
  if (id == kCfgDat) {  // the current datum becomes this user datum
    CfgDat set;
    decode(p, set);
    CfgDatCurrent m;
    static_cast<CfgDat&>(m) = set;
    m.datum_num = 0xFFFF;
    m.datum_name = "USER";
    ram_[{key_of(id), 0}] = encoded(m);
    return true;
  }
  const std::uint8_t index = id == kCfgTp5 ? p[0] : 0;
  Bytes& kept = ram_[{key_of(id), index}];
  if (kept.empty()) kept = power_up(id, index, protocol27_);
  if (e->extends && p.size() < kept.size())
    std::copy(p.begin(), p.end(), kept.begin());  // a shorter form sets the fields it has
  else
    kept.assign(p.begin(), p.end());
  return true;
}

}  // namespace navemu
