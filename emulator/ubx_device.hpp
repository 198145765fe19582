#pragma once
// A u-blox receiver's device behaviour (u-blox 8 / M8 receiver description UBX-13003221 and the
// F9 interface description UBX-18010854): the configuration a client changes (its layered
// database, emulator/ubx_config.hpp, reached through CFG-VALSET/VALGET/VALDEL on protocol 27+
// and through the legacy CFG messages on every part), answers to polls, ACK-ACK for accepted
// configuration and ACK-NAK for what the part refuses, and each epoch's output per port: the
// enabled UBX messages (emulator/ubx_outputs.hpp) and NMEA, each when the port's output
// protocols include it. A port whose input protocols include NMEA also takes the NMEA input
// the part accepts (PUBX,40/41, PUBX and standard polls: emulator/ubx_nmea_input.cpp).

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "emulator/gnss_device.hpp"
#include "emulator/nmea_output.hpp"
#include "emulator/ubx_config.hpp"
#include "emulator/ubx_legacy_cfg.hpp"
#include "emulator/ubx_outputs.hpp"
#include "models/survey_in.hpp"
#include "protocols/pubx.hpp"
#include "protocols/ubx.hpp"
#include "protocols/ubx_messages.hpp"

namespace navemu {

struct UbxDeviceCounters {
  std::uint64_t frames = 0, acks = 0, naks = 0, polls = 0;
  std::uint64_t checksum_errors = 0, too_long = 0, junk_bytes = 0;
  // NMEA input: commands taken, and complete lines ignored (bad checksum or framing, too
  // long, not an input of the part, a bad field, NMEA not in the port's input protocols).
  std::uint64_t nmea_commands = 0, nmea_ignored = 0;
};

class UbxDevice final : public GnssDevice {
 public:
  UbxDevice(const GnssProfile& profile, ReceiverMode mode, const NavData& nav);

  using GnssDevice::receive;
  using GnssDevice::take_baud_change;
  const ReceiverFix& reported_fix() const override { return last_fix_; }
  void encode(ReceiverPort port, std::string& out) override;
  void receive(std::span<const std::uint8_t> bytes, ReceiverPort port, std::string& replies) override;
  std::int64_t period_ns() const override { return period_ns_; }
  std::int64_t grid_offset_ns(GpsTime t) const override;
  std::optional<int> take_baud_change(ReceiverPort port) override;
  void restart(RestartKind kind, bool hardware, GpsTime t) override;
  const NavEngineSettings* engine_settings() const override { return &engine_; }

  UbxDeviceCounters counters() const;
  // The rate (every n-th solution, 0 off) of a message on a port (u-blox port ID).
  int rate(ubx::MsgId id, std::uint8_t port = ubx::kPortUart1) const;
  const UbxConfig& config() const { return config_; }

 private:
  using Bytes = std::vector<std::uint8_t>;
  void take_epoch(const ReceiverFix& fix, const EpochMeasurements& meas, std::int64_t epoch_index) override;
  using Payload = std::span<const std::uint8_t>;
  struct Command;
  static const Command kCommands[];
  // What the configuration says, in the form the output needs; refreshed when it changes.
  struct PortSettings {
    bool in_ubx = true, in_nmea = true, out_ubx = true, out_nmea = true;
    int baud = 0;  // UARTs
    std::array<std::uint8_t, kMaxUbxOutputs> ubx_rates{};  // by index in ubx_outputs()
    std::unique_ptr<NmeaOutput> nmea;          // this port's sentences and their rates
  };
  void refresh();
  void refresh_time_mode();
  std::uint32_t msgout_key(ubx::MsgId id, std::uint8_t port) const;  // 0: none
  void set_keys(std::initializer_list<ubx::CfgKeyValue> values);
  void set_rate(ubx::MsgId id, std::uint8_t port, int rate);

  void handle(std::uint8_t cls, std::uint8_t id, Payload payload, std::uint8_t port, Bytes& out);
  void ack(ubx::MsgId msg, Bytes& out);
  void nak(ubx::MsgId msg, Bytes& out);
  void poll_mon_ver(std::uint8_t port, Bytes& out);
  void poll_mon_gnss(std::uint8_t port, Bytes& out);
  void poll_mon_patch(std::uint8_t port, Bytes& out);
  void poll_sec_uniqid(std::uint8_t port, Bytes& out);
  void handle_nav_resetodo(Payload payload, std::uint8_t port, Bytes& out);
  void poll_aid_ini(std::uint8_t port, Bytes& out);
  void poll_aid_hui(std::uint8_t port, Bytes& out);
  void poll_aid_alm(std::uint8_t port, Bytes& out);
  void poll_aid_eph(std::uint8_t port, Bytes& out);
  void poll_aid_aop(std::uint8_t port, Bytes& out);
  std::optional<int> aid_poll_svid(Payload payload);
  void handle_aid_alm(Payload payload, std::uint8_t port, Bytes& out);
  void handle_aid_eph(Payload payload, std::uint8_t port, Bytes& out);
  void handle_aid_aop(Payload payload, std::uint8_t port, Bytes& out);
  void poll_mga_dbd(std::uint8_t port, Bytes& out);
  void acknowledge_aiding(ubx::MsgId msg, Payload payload, Bytes& out);
  void poll_upd_sos(std::uint8_t port, Bytes& out);
  void handle_upd_sos(Payload payload, std::uint8_t port, Bytes& out);
  void poll_cfg_rate(std::uint8_t port, Bytes& out);
  void poll_cfg_nav5(std::uint8_t port, Bytes& out);
  void poll_cfg_gnss(std::uint8_t port, Bytes& out);
  ubx::CfgGnss current_cfg_gnss() const;
  void handle_cfg_prt(Payload payload, std::uint8_t port, Bytes& out);
  void handle_cfg_msg(Payload payload, std::uint8_t port, Bytes& out);
  void handle_cfg_rate(Payload payload, std::uint8_t port, Bytes& out);
  void handle_cfg_nav5(Payload payload, std::uint8_t port, Bytes& out);
  void poll_cfg_tmode3(std::uint8_t port, Bytes& out);
  void handle_cfg_inf(Payload payload, std::uint8_t port, Bytes& out);
  void poll_cfg_itfm(std::uint8_t port, Bytes& out);
  void handle_cfg_itfm(Payload payload, std::uint8_t port, Bytes& out);
  void poll_cfg_odo(std::uint8_t port, Bytes& out);
  void handle_cfg_odo(Payload payload, std::uint8_t port, Bytes& out);
  void poll_cfg_nmea(std::uint8_t port, Bytes& out);
  void handle_cfg_nmea(Payload payload, std::uint8_t port, Bytes& out);
  void handle_cfg_tp5(Payload payload, std::uint8_t port, Bytes& out);
  void handle_cfg_tmode3(Payload payload, std::uint8_t port, Bytes& out);
  void handle_cfg_gnss(Payload payload, std::uint8_t port, Bytes& out);
  void handle_cfg_cfg(Payload payload, std::uint8_t port, Bytes& out);
  void handle_cfg_rst(Payload payload, std::uint8_t port, Bytes& out);
  void handle_valset(Payload payload, std::uint8_t port, Bytes& out);
  void handle_valget(Payload payload, std::uint8_t port, Bytes& out);
  void handle_valdel(Payload payload, std::uint8_t port, Bytes& out);
  bool output_message(ubx::MsgId id, Bytes& out);
  void count_distance(const ReceiverFix& fix);
  void hold_time_mode_position(ReceiverFix& fix);
  // A port's protocol masks (ubx::kProto*) and baud (0: unchanged) as configuration items
  // (CFG-PRT, PUBX,41).
  void port_values(std::uint8_t port, std::uint16_t in_mask, std::uint16_t out_mask, std::uint32_t baud,
                   std::vector<ubx::CfgKeyValue>& values) const;
  // An NMEA sentence received on `port` (emulator/ubx_nmea_input.cpp).
  void receive_nmea(std::string_view sentence, std::uint8_t port, Bytes& out);
  // An information message of `type` (0 error, 1 warning, 2 notice, 3 test, 4 debug) on `port`.
  void inform(std::uint8_t port, std::uint8_t type, std::string_view text, Bytes& out);

  GnssProfile profile_;
  ReceiverMode mode_;
  const NavData& nav_;
  bool protocol27_;
  struct Keys {
    std::uint32_t rate_meas, rate_nav, rate_timeref;
    std::array<std::uint32_t, 3> tmode;  // CFG-TMODE-MODE, -SVIN_MIN_DUR, -SVIN_ACC_LIMIT
  } keys_;
  std::array<ubx::Parser, kReceiverPorts> parsers_;
  std::array<pubx::NmeaInputReader, kReceiverPorts> nmea_in_;
  UbxDeviceCounters counters_;
  UbxConfig config_;
  UbxLegacyCfg legacy_;
  std::uint64_t seen_generation_ = 0;
  bool stale_ = true;  // refresh() must run even if the database did not change
  std::int64_t period_ns_ = 1'000'000'000;
  std::uint64_t time_ref_ = 1;  // CFG-RATE-TIMEREF
  std::array<PortSettings, kReceiverPorts> ports_;
  std::array<std::optional<int>, kReceiverPorts> pending_baud_;
  // Rates of messages without a CFG-MSGOUT item on this part (u-blox 8 only messages, and
  // messages the receiver does not send but takes a rate for): (class << 8 | id) -> per port.
  std::map<std::uint16_t, std::array<std::uint8_t, ubx::kNumPorts>> other_rates_;
  bool sos_backup_ = false;    // a backup in flash (UPD-SOS create)
  bool sos_restored_ = false;  // the last start restored it

  NavEngineSettings engine_;  // from CFG-NAVSPG
  std::string talker_;        // the NMEA talker ID the output uses (CFG-NMEA-MAINTALKERID)
  std::optional<int> nmea_version_;  // CFG-NMEA-PROTVER (the u-blox 8: legacy CFG-NMEA); none: the profile's
  // What the monitor and odometer messages report (traffic, odometer, switches).
  UbxDeviceStatus status_;
  std::optional<GpsTime> odo_last_t_;  // the previous fix the odometer counted from
  // The time mode (F9): a survey-in starts anew when its settings change or the receiver resets.
  SurveyIn survey_;
  std::optional<std::array<std::uint64_t, 3>> survey_settings_;  // the settings it started with
  // Time mode "fixed" (CFG-TMODE-MODE 2): the configured antenna position and its accuracy.
  struct FixedPosition {
    Vec3 p_ecef_m = Vec3::Zero();
    double acc_m = 0.0;
  };
  std::optional<FixedPosition> fixed_position_;

  // The latest epoch, for the output and polled messages and the restart clock.
  ReceiverFix last_fix_;
  ReceiverFix nmea_fix_;  // last_fix_ as NMEA reports it when outside the output filters
  bool fix_filtered_out_ = false;
  EpochMeasurements last_meas_;
  std::int64_t epoch_index_ = 0;
  Bytes scratch_;
  UbxListScratch lists_;
};

}  // namespace navemu
