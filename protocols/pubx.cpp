// u-blox NMEA input and PUBX output. Message layouts: u-blox 8 / u-blox M8 Receiver
// description (UBX-13003221), "PUBX Messages" and "Standard Messages"; the F9 interface
// descriptions (UBX-18010854, UBX-21023318) for the GxQ polls; field widths from real
// receiver output (tests/protocols/test_pubx.cpp). See pubx.hpp.
#include "protocols/pubx.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>

#include "protocols/nmea_fields.hpp"

namespace navemu::pubx {

using nmea::detail::Line;

// ---- input reader -----------------------------------------------------------------------

NmeaInputReader::NmeaInputReader(std::size_t max_sentence)
    : buf_(std::max<std::size_t>(max_sentence, 8)) {}

void NmeaInputReader::reset() {
  state_ = State::kIdle;
  n_ = 0;
}

void NmeaInputReader::start() {
  state_ = State::kLine;
  buf_[0] = '$';
  n_ = 1;
}

std::optional<std::string_view> NmeaInputReader::feed(std::uint8_t byte) {
  const char c = static_cast<char>(byte);
  switch (state_) {
    case State::kIdle:
      if (c == '$') start();
      return std::nullopt;
    case State::kSkip:
      if (c == '$') start();
      if (c == '\n') state_ = State::kIdle;
      return std::nullopt;
    case State::kLine: break;
  }
  if (c == '\n') {
    buf_[n_++] = c;  // start() and the overlong check below leave room for it
    state_ = State::kIdle;
    const std::string_view line(buf_.data(), n_);
    switch (nmea::check(line).status) {
      case nmea::Checked::kOk: ++counters_.sentences; return line;
      case nmea::Checked::kBadChecksum: ++counters_.checksum_errors; return std::nullopt;
      case nmea::Checked::kMalformed: ++counters_.malformed; return std::nullopt;
    }
    return std::nullopt;
  }
  if (c == '$' || ((byte < 0x20 || byte > 0x7E) && c != '\r')) {
    ++counters_.abandoned;
    if (c == '$') {
      start();
    } else {
      state_ = State::kIdle;
    }
    return std::nullopt;
  }
  if (n_ + 1 >= buf_.size()) {  // no room left for this byte and the LF after it
    ++counters_.overlong;
    state_ = State::kSkip;
    return std::nullopt;
  }
  buf_[n_++] = c;
  return std::nullopt;
}

// ---- parsing ----------------------------------------------------------------------------

namespace {

// The fields of a sentence body, split at ',' without allocating; more than kMax fields are
// counted but not kept.
struct Fields {
  static constexpr std::size_t kMax = 10;
  std::array<std::string_view, kMax> f;
  std::size_t n = 0;

  explicit Fields(std::string_view body) {
    for (std::size_t start = 0;;) {
      const std::size_t comma = body.find(',', start);
      if (n < kMax) f[n] = body.substr(start, comma - start);
      ++n;
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
  }
};

bool is_upper(char c) { return c >= 'A' && c <= 'Z'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

bool all_upper(std::string_view s) { return std::all_of(s.begin(), s.end(), is_upper); }

// A decimal number of 1 to 10 digits.
std::optional<std::uint64_t> decimal(std::string_view s) {
  if (s.empty() || s.size() > 10 || !std::all_of(s.begin(), s.end(), is_digit)) return std::nullopt;
  std::uint64_t v = 0;
  for (char c : s) v = v * 10 + static_cast<std::uint64_t>(c - '0');
  return v;
}

// A hexadecimal number of 1 to 4 digits (an X2 mask), either case.
std::optional<std::uint16_t> hex16(std::string_view s) {
  if (s.empty() || s.size() > 4) return std::nullopt;
  unsigned v = 0;
  for (char c : s) {
    int d = -1;
    if (is_digit(c)) d = c - '0';
    if (c >= 'A' && c <= 'F') d = c - 'A' + 10;
    if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
    if (d < 0) return std::nullopt;
    v = v * 16 + static_cast<unsigned>(d);
  }
  return static_cast<std::uint16_t>(v);
}

Parsed reject(Reason r, std::size_t field = 0, std::string_view name = {}) {
  return {std::nullopt, r, field, name};
}

Parsed accept(Command c) { return {c, Reason::kAccepted, 0, {}}; }

// PUBX,40: PUBX,40,msgId,rddc,rus1,rus2,rusb,rspi,reserved (at least one rate).
Parsed parse_rate(const Fields& f) {
  static constexpr std::array<std::string_view, kPortCount> kNames{"rddc", "rus1", "rus2", "rusb",
                                                                   "rspi"};
  if (f.n < 4 || f.n > 9) return reject(Reason::kFieldCount, f.n);
  if (f.f[2].size() != 3 || !all_upper(f.f[2])) return reject(Reason::kBadField, 2, "msgId");
  SetRate c;
  c.msg_id = Formatter::of(f.f[2]);
  for (std::size_t p = 0; p < kPortCount && 3 + p < f.n; ++p) {
    const std::string_view s = f.f[3 + p];
    if (s.empty()) continue;
    const auto v = decimal(s);
    if (!v) return reject(Reason::kBadField, 3 + p, kNames[p]);
    if (*v > 255) return reject(Reason::kOutOfRange, 3 + p, kNames[p]);
    c.rate[p] = static_cast<std::uint8_t>(*v);
  }
  if (f.n == 9 && !f.f[8].empty() && !decimal(f.f[8]))
    return reject(Reason::kBadField, 8, "reserved");
  return accept(c);
}

// PUBX,41: PUBX,41,portId,inProto,outProto,baudrate,autobauding.
Parsed parse_port(const Fields& f) {
  if (f.n != 7) return reject(Reason::kFieldCount, f.n);
  SetPort c;
  const auto port = decimal(f.f[2]);
  if (!port) return reject(Reason::kBadField, 2, "portId");
  if (*port >= kPortCount) return reject(Reason::kOutOfRange, 2, "portId");
  c.port = static_cast<PortId>(*port);
  const auto in = hex16(f.f[3]);
  if (!in) return reject(Reason::kBadField, 3, "inProto");
  const auto out = hex16(f.f[4]);
  if (!out) return reject(Reason::kBadField, 4, "outProto");
  c.in_proto = *in;
  c.out_proto = *out;
  const auto baud = decimal(f.f[5]);
  if (!baud) return reject(Reason::kBadField, 5, "baudrate");
  if (*baud == 0 || *baud > 0xFFFFFFFFu) return reject(Reason::kOutOfRange, 5, "baudrate");
  c.baud_rate = static_cast<std::uint32_t>(*baud);
  if (f.f[6] != "0" && f.f[6] != "1") return reject(Reason::kBadField, 6, "autobauding");
  c.autobauding = f.f[6] == "1";
  return accept(c);
}

// $xxLLQ,msgId: requester xx, listener LL.
constexpr std::array<std::string_view, 6> kPollListeners{"GP", "GN", "GL", "GB", "GA", "GQ"};

Parsed parse_standard_poll(const Fields& f) {
  const std::string_view addr = f.f[0];
  const std::string_view listener = addr.substr(2, 2);
  if (!all_upper(addr.substr(0, 2)) ||
      std::find(kPollListeners.begin(), kPollListeners.end(), listener) == kPollListeners.end())
    return reject(Reason::kNotInput);
  if (f.n != 2) return reject(Reason::kFieldCount, f.n);
  if (f.f[1].size() != 3 || !all_upper(f.f[1])) return reject(Reason::kBadField, 1, "msgId");
  return accept(
      PollStandard{Talker::of(addr.substr(0, 2)), Talker::of(listener), Formatter::of(f.f[1])});
}

}  // namespace

std::string_view to_string(Reason r) {
  switch (r) {
    case Reason::kAccepted: return "accepted";
    case Reason::kMalformed: return "malformed sentence";
    case Reason::kBadChecksum: return "checksum mismatch";
    case Reason::kNotInput: return "not an input of the receiver";
    case Reason::kFieldCount: return "wrong number of fields";
    case Reason::kBadField: return "field of the wrong form";
    case Reason::kOutOfRange: return "field out of range";
  }
  return "?";
}

Parsed parse_input(std::string_view sentence) {
  const nmea::Checked checked = nmea::check(sentence);
  if (checked.status == nmea::Checked::kMalformed) return reject(Reason::kMalformed);
  if (checked.status == nmea::Checked::kBadChecksum) return reject(Reason::kBadChecksum);
  const Fields f(checked.body);
  const std::string_view addr = f.f[0];
  if (addr == "PUBX") {
    if (f.n < 2) return reject(Reason::kFieldCount, f.n);
    const std::string_view id = f.f[1];
    if (id == "40") return parse_rate(f);
    if (id == "41") return parse_port(f);
    if (id == "00" || id == "03" || id == "04") {
      // "polled by sending the PUBX,0x message without any data fields"
      if (f.n != 2) return reject(Reason::kFieldCount, f.n);
      return accept(PollPubx{static_cast<std::uint8_t>(id[1] - '0')});
    }
    return reject(Reason::kNotInput, 1, "msgId");
  }
  if (addr.size() == 5 && addr[4] == 'Q') return parse_standard_poll(f);
  return reject(Reason::kNotInput);
}

// ---- encoding ---------------------------------------------------------------------------

namespace {

std::string_view nav_status_code(NavStatus s) {
  switch (s) {
    case NavStatus::kNoFix: return "NF";
    case NavStatus::kDeadReckoning: return "DR";
    case NavStatus::kStandalone2D: return "G2";
    case NavStatus::kStandalone3D: return "G3";
    case NavStatus::kDifferential2D: return "D2";
    case NavStatus::kDifferential3D: return "D3";
    case NavStatus::kGnssDeadReckoning: return "RK";
    case NavStatus::kTimeOnly: return "TT";
  }
  return "NF";
}

char use_code(SvUse u) {
  switch (u) {
    case SvUse::kUsed: return 'U';
    case SvUse::kEphemerisNotUsed: return 'e';
    case SvUse::kNotUsed: return '-';
  }
  return '-';
}

int time_decimals(const nmea::Format& fmt) { return std::clamp(fmt.time_decimals, 0, 3); }

// A value in SI units scaled to wire units, then clamped; nothing when unset or not finite.
std::optional<double> scaled(std::optional<double> v, double scale, double lo, double hi) {
  if (v) *v *= scale;
  return nmea::detail::valid(v, lo, hi);
}

}  // namespace

void encode(const PositionFields& f, const nmea::Format& fmt, std::string& out) {
  using namespace nmea::detail;
  Line l("P", "UBX,00,");
  put_time(l, stamp(f.utc, time_decimals(fmt)));
  put_position(l, f.position, std::clamp(fmt.latlon_minute_decimals, 0, 5));
  l.sep();
  put_fixed(l, valid(f.height_user_datum_m, -99999.999, 999999.999), 3);
  l.sep();
  l.text(nav_status_code(f.nav_status));
  l.sep();
  put_significant(l, valid(f.h_acc_m, 0.0, 9999999.0), 2);
  l.sep();
  put_significant(l, valid(f.v_acc_m, 0.0, 9999999.0), 2);
  l.sep();
  put_fixed(l, scaled(f.speed_mps, nmea::detail::kMpsToKmh, 0.0, 99999.999), 3);
  l.sep();
  put_course(l, valid(f.course_deg, -1e9, 1e9), 2, 1);
  l.sep();
  put_fixed(l, valid(f.velocity_down_mps, -9999.999, 9999.999), 3);
  l.sep();
  put_fixed(l, valid(f.diff_age_s, 0.0, 999.9), 1);
  for (const auto& dop : {f.hdop, f.vdop, f.tdop}) {
    l.sep();
    put_fixed(l, valid(dop, 0.0, 99.99), 2);
  }
  l.format(",{},0,{}", std::clamp(f.num_svs, 0, 255), f.dead_reckoning_used ? 1 : 0);
  l.finish(out);
}

void encode(const SvStatusFields& f, std::string& out) {
  // Written straight into `out`: the sentence has no length bound.
  const std::size_t start = out.size();
  auto it = std::back_inserter(out);
  fmt::format_to(it, "$PUBX,03,{}", f.satellites.size());
  for (const SvStatus& s : f.satellites) {
    fmt::format_to(it, ",{},{},", std::clamp(s.sv_id, 0, 999), use_code(s.use));
    if (s.azimuth_deg) fmt::format_to(it, "{:03d}", (*s.azimuth_deg % 360 + 360) % 360);
    out += ',';
    if (s.elevation_deg) fmt::format_to(it, "{:02d}", std::clamp(*s.elevation_deg, -90, 90));
    out += ',';
    if (s.cno_dbhz) fmt::format_to(it, "{:02d}", std::clamp(*s.cno_dbhz, 0, 99));
    const double lock = std::isfinite(s.carrier_lock_s) ? s.carrier_lock_s : 0.0;
    fmt::format_to(it, ",{:03d}", static_cast<int>(std::clamp(std::floor(lock), 0.0, 64.0)));
  }
  const std::string_view body = std::string_view(out).substr(start + 1);
  fmt::format_to(it, "*{:02X}\r\n", nmea::checksum(body));
}

void encode(const TimeFields& f, const nmea::Format& fmt, std::string& out) {
  using namespace nmea::detail;
  Line l("P", "UBX,04,");
  const Stamp t = stamp(f.utc, time_decimals(fmt));
  put_time(l, t);
  l.format(",{:02d}{:02d}{:02d},", t.day, t.month, t.year % 100);
  put_fixed(l, valid(f.utc_tow_s, 0.0, 604800.0), 2);
  l.sep();
  if (f.utc_week) l.format("{}", std::clamp(*f.utc_week, 0, 99999));
  l.sep();
  if (f.leap_seconds) {
    l.format("{}", std::clamp(*f.leap_seconds, -99, 99));
    if (f.leap_seconds_default) l.put('D');
  }
  l.sep();
  if (const auto bias_ns = scaled(f.clock_bias_s, 1e9, -999.999e9, 999.999e9))
    l.format("{}", std::llround(*bias_ns));
  l.sep();
  put_fixed(l, scaled(f.clock_drift_s_per_s, 1e9, -1e6, 1e6), 3);
  l.sep();
  if (const auto gran_ns = scaled(f.time_pulse_granularity_s, 1e9, 0.0, 999.0))
    l.format("{:02d}", std::llround(*gran_ns));
  l.finish(out);
}

namespace {

void encode_command(const SetRate& c, Line& l) {
  l.format(",40,{}", c.msg_id.view());
  std::size_t n = kPortCount;
  while (n > 0 && !c.rate[n - 1]) --n;
  for (std::size_t p = 0; p < n; ++p) {
    l.sep();
    if (c.rate[p]) l.format("{}", *c.rate[p]);
  }
  if (n == kPortCount) l.text(",0");  // reserved
}

void encode_command(const SetPort& c, Line& l) {
  l.format(",41,{},{:04X},{:04X},{},{}", static_cast<int>(c.port), c.in_proto, c.out_proto,
           c.baud_rate, c.autobauding ? 1 : 0);
}

void encode_command(const PollPubx& c, Line& l) { l.format(",{:02d}", c.msg_id); }

}  // namespace

void encode(const Command& c, std::string& out) {
  if (const auto* poll = std::get_if<PollStandard>(&c)) {
    Line l(poll->requester.view(), poll->listener.view());
    l.format("Q,{}", poll->msg_id.view());
    l.finish(out);
    return;
  }
  Line l("P", "UBX");
  std::visit(
      [&](const auto& cmd) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(cmd)>, PollStandard>)
          encode_command(cmd, l);
      },
      c);
  l.finish(out);
}

}  // namespace navemu::pubx
