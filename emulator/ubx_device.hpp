#pragma once
// A u-blox receiver's device behaviour (u-blox 8 / M8 Receiver Description UBX-13003221 and
// the F9 interface descriptions): the configuration state a client changes with CFG messages
// (port protocols and baud, message rates, measurement rate, navigation settings, restarts),
// answers to polls, ACK-ACK for accepted configuration and ACK-NAK for what it does not know,
// and each epoch's output: the enabled UBX messages (NAV-*, RXM-RAWX, RXM-SFRBX) built from
// the receiver model, and NMEA when the port's output mask includes it.

#include <array>
#include <map>
#include <memory>
#include <vector>

#include "emulator/gnss_device.hpp"
#include "protocols/ubx.hpp"
#include "protocols/ubx_messages.hpp"

namespace navemu {

// Messages with lists, refilled every epoch (the lists keep their storage, so encoding an epoch
// does not allocate once they have grown).
struct UbxListScratch {
  ubx::NavSvinfo svinfo;
  ubx::NavSat sat;
  ubx::RxmRawx rawx;
  ubx::RxmSfrbx sfrbx;
};

struct UbxDeviceCounters {
  std::uint64_t frames = 0, acks = 0, naks = 0, polls = 0;
  std::uint64_t checksum_errors = 0, too_long = 0, junk_bytes = 0;
};

class UbxDevice final : public GnssDevice {
 public:
  UbxDevice(const GnssProfile& profile, ReceiverMode mode, const NavData& nav);

  void encode_epoch(const ReceiverFix& fix, const EpochMeasurements& meas,
                    std::int64_t epoch_index, std::string& out) override;
  void receive(std::span<const std::uint8_t> bytes, std::string& replies) override;
  std::int64_t period_ns() const override;
  std::optional<int> take_baud_change() override;
  bool restarting(GpsTime t) const override { return t < restart_until_; }

  UbxDeviceCounters counters() const;
  // The rate (every n-th solution, 0 off) of a message on a port (default: the one emulated,
  // UART1; the other ports' rates are kept for polls).
  int rate(ubx::MsgId id, std::uint8_t port = ubx::kPortUart1) const;

 private:
  using Bytes = std::vector<std::uint8_t>;
  using Payload = std::span<const std::uint8_t>;
  // Dispatch of a received frame through kCommands (configuration and polls), else a poll of
  // an output message.
  struct Command;
  static const Command kCommands[];
  void handle(std::uint8_t cls, std::uint8_t id, Payload payload, Bytes& out);
  void ack(ubx::MsgId msg, Bytes& out);
  void nak(ubx::MsgId msg, Bytes& out);
  void poll_mon_ver(Bytes& out);
  void poll_mon_hw(Bytes& out);
  void poll_cfg_rate(Bytes& out);
  void poll_cfg_nav5(Bytes& out);
  void poll_cfg_gnss(Bytes& out);
  void handle_cfg_prt(Payload payload, Bytes& out);
  void handle_cfg_msg(Payload payload, Bytes& out);
  void handle_cfg_rate(Payload payload, Bytes& out);
  void handle_cfg_nav5(Payload payload, Bytes& out);
  void handle_cfg_gnss(Payload payload, Bytes& out);
  void handle_cfg_cfg(Payload payload, Bytes& out);
  void handle_cfg_rst(Payload payload, Bytes& out);
  void handle_valset(Payload payload, Bytes& out);
  void handle_valget(Payload payload, Bytes& out);
  void handle_valdel(Payload payload, Bytes& out);
  template <class Msg>
  void accept_well_formed(Payload payload, Bytes& out);
  std::optional<std::uint64_t> value_of(std::uint32_t key_id) const;  // a CFG-VALGET key
  bool output_message(ubx::MsgId id, std::vector<std::uint8_t>& out) const;
  void rebuild_nmea();
  void set_rate(ubx::MsgId id, std::uint8_t port, int rate);

  GnssProfile profile_;
  ReceiverMode mode_;
  const NavData& nav_;
  std::unique_ptr<NmeaOutput> nmea_;
  ubx::Parser parser_;
  UbxDeviceCounters counters_;

  // Configuration state (RAM layer).
  std::uint8_t port_id_ = ubx::kPortUart1;
  int baud_ = 9600;
  std::optional<int> pending_baud_;
  std::uint16_t in_proto_ = ubx::kProtoUbx | ubx::kProtoNmea;
  std::uint16_t out_proto_ = ubx::kProtoUbx | ubx::kProtoNmea;
  // (class << 8 | id) -> every n-th solution, per port ID (CFG-MSG's six ports).
  std::map<std::uint16_t, std::array<std::uint8_t, ubx::kNumPorts>> rates_;
  std::uint16_t meas_rate_ms_ = 1000;
  std::uint16_t nav_rate_ = 1;
  std::uint16_t time_ref_ = ubx::CfgRate::kTimeRefGps;
  ubx::CfgNav5 nav5_;
  ubx::CfgGnss gnss_;
  GpsTime restart_until_{0};
  std::map<std::uint32_t, std::uint64_t> usb_proto_keys_;

  // The latest epoch, for polled NAV messages and the restart clock.
  ReceiverFix last_fix_;
  EpochMeasurements last_meas_;
  std::vector<std::uint8_t> scratch_;
  // Output messages with lists (output_message is const because polls use it too).
  mutable UbxListScratch lists_;
};

}  // namespace navemu
