#pragma once
// The legacy CFG messages whose settings navemu keeps without modelling them (u-blox 8 / M8
// receiver description UBX-13003221 section 32.10 "UBX-CFG"; the F9 interface descriptions
// keep most of them, deprecated, beside the configuration database): a set in any documented
// form is checked against the message's layout (protocols/ubx_messages.hpp) and kept; a poll
// is answered with what was set, or with the part's power-up values. Each part has only the
// messages its description lists; the device answers the others with ACK-NAK.
//
// Like the part's other settings, what was set is lost at a reset unless CFG-CFG saved it.

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "protocols/ubx_messages.hpp"

namespace navemu {

// The ports the parts set alike at power-up: every port but UART2, an RTCM port on the F9 (F9
// HPG 1.13 description, CFG-UART2OUTPROT defaults).
inline constexpr std::array<std::uint8_t, 4> kPortsButUart2 = {ubx::kPortDdc, ubx::kPortUart1, ubx::kPortUsb,
                                                               ubx::kPortSpi};

// The u-blox 8's power-up CFG-GNSS (M8 receiver description UBX-13003221 "GNSS
// configuration", default set of the standard-precision parts): GPS, SBAS, QZSS and GLONASS on,
// Galileo, BeiDou and IMES off; channels (reserved, maximum) GPS 8/16, SBAS 1/3, Galileo 4/8,
// BeiDou 8/16, IMES 0/8, QZSS 0/3, GLONASS 8/14 of 32; each with its L1 signal (sigCfgMask 0x01).
ubx::CfgGnss m8_power_up_gnss();

class UbxLegacyCfg {
 public:
  explicit UbxLegacyCfg(bool protocol27);

  // Whether this part has the message.
  bool has(ubx::MsgId id) const;
  // A payload for a message the part has: a poll (its payload is empty, or the poll form's
  // index) appends the answer frame to `out` and returns true; a set is kept when it decodes in
  // one of the message's forms (true) or refused (false).
  bool handle(ubx::MsgId id, std::span<const std::uint8_t> payload, std::vector<std::uint8_t>& out);
  // The setting as the part has it now (set-form payload): what was set, or the power-up value.
  std::vector<std::uint8_t> current(ubx::MsgId id, std::uint8_t index = 0) const;

  // CFG-CFG: keep what was set over a reset, forget it, or go back to what was kept.
  void save() { saved_ = ram_; }
  void clear() { saved_.clear(); }
  void load() { ram_ = saved_; }

 private:
  // Settings by message and index (CFG-INF: protocol, CFG-TP5: time pulse), as set-form
  // payloads.
  using Key = std::pair<std::uint16_t, std::uint8_t>;
  bool protocol27_;
  std::map<Key, std::vector<std::uint8_t>> ram_, saved_;
};

}  // namespace navemu
