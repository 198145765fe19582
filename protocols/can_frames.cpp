#include "can_frames.hpp"

#include <cmath>
#include <limits>

namespace navemu::can {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

void put_u16_le(std::span<std::uint8_t> out, std::size_t at, std::uint16_t v) {
  out[at] = static_cast<std::uint8_t>(v & 0xFFu);
  out[at + 1] = static_cast<std::uint8_t>(v >> 8);
}

void put_u32_le(std::span<std::uint8_t> out, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) {
    out[at + i] = static_cast<std::uint8_t>((v >> (8 * i)) & 0xFFu);
  }
}

void put_u64_le(std::span<std::uint8_t> out, std::size_t at, std::uint64_t v) {
  for (std::size_t i = 0; i < 8; ++i) {
    out[at + i] = static_cast<std::uint8_t>((v >> (8 * i)) & 0xFFu);
  }
}

std::uint16_t get_u16_le(std::span<const std::uint8_t> in, std::size_t at) {
  return static_cast<std::uint16_t>(in[at] | (in[at + 1] << 8));
}

std::uint32_t get_u32_le(std::span<const std::uint8_t> in, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(in[at + i]) << (8 * i);
  return v;
}

std::uint64_t get_u64_le(std::span<const std::uint8_t> in, std::size_t at) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(in[at + i]) << (8 * i);
  return v;
}

j1939::FigureOfMerit worst(j1939::FigureOfMerit a, j1939::FigureOfMerit b) {
  return static_cast<std::uint8_t>(a) >= static_cast<std::uint8_t>(b) ? a : b;
}

// Bytes 1-6 three 2-byte parameters, byte 7 three 2-bit figures of merit and 11b in bits 7-8,
// byte 8 latency (layout table in the header).
CanFrame build_j1939(std::uint32_t pgn, const j1939::Config& config,
                     const std::array<j1939::Raw16, 3>& values, std::uint8_t latency) {
  CanFrame frame;
  frame.id = j1939::make_id(config.priority, pgn, config.source_address);
  frame.extended = true;
  frame.fd = false;
  frame.len = 8;
  std::uint8_t status = 0xC0;  // bits 7-8: not defined/not available
  for (std::size_t i = 0; i < 3; ++i) {
    put_u16_le(frame.data, 2 * i, values[i].raw);
    status = static_cast<std::uint8_t>(status | (static_cast<std::uint8_t>(values[i].fom) << (2 * i)));
  }
  frame.data[6] = status;
  frame.data[7] = latency;
  return frame;
}

j1939::Raw16 with_flag(j1939::Raw16 r, bool degraded) {
  if (degraded) r.fom = worst(r.fom, j1939::FigureOfMerit::kDegraded);
  return r;
}

struct Int32Result {
  std::int32_t raw = 0;
  bool saturated = false;
};

Int32Result to_int32(double value, double lsb) {
  if (!std::isfinite(value)) return {std::numeric_limits<std::int32_t>::min(), true};
  const double scaled = std::round(value / lsb);
  constexpr double kMax = static_cast<double>(std::numeric_limits<std::int32_t>::max());
  constexpr double kMin = static_cast<double>(std::numeric_limits<std::int32_t>::min());
  if (scaled > kMax) return {std::numeric_limits<std::int32_t>::max(), true};
  if (scaled < kMin) return {std::numeric_limits<std::int32_t>::min(), true};
  return {static_cast<std::int32_t>(scaled), false};
}

// The 36 CRC-covered bytes, in FD order (see the header).
std::array<std::uint8_t, highres::kCrcInputSize> highres_payload(const ImuSample& sample) {
  std::array<std::uint8_t, highres::kCrcInputSize> p{};
  put_u64_le(p, 0, static_cast<std::uint64_t>(sample.gps_time_ns));
  std::uint8_t flags = sample.truth_lost ? highres::kFlagTruthLost : 0;
  if (sample.gyro_saturated) flags |= highres::kFlagGyroSaturated;
  if (sample.accel_saturated) flags |= highres::kFlagAccelSaturated;
  for (std::size_t i = 0; i < 3; ++i) {
    const Int32Result w = to_int32(sample.w_body_radps[i], highres::kRateLsbRadps);
    const Int32Result f = to_int32(sample.f_body_mps2[i], highres::kAccelLsbMps2);
    put_u32_le(p, 8 + 4 * i, static_cast<std::uint32_t>(w.raw));
    put_u32_le(p, 20 + 4 * i, static_cast<std::uint32_t>(f.raw));
    if (w.saturated) flags |= highres::kFlagGyroSaturated;
    if (f.saturated) flags |= highres::kFlagAccelSaturated;
  }
  put_u16_le(p, 32, sample.sequence);
  p[34] = flags;
  p[35] = 0;
  return p;
}

CanFrame make_frame(const highres::Config& config, std::uint32_t offset, bool fd,
                    std::uint8_t len) {
  CanFrame f;
  f.id = (config.base_id + offset) & (config.extended ? 0x1FFFFFFFu : 0x7FFu);
  f.extended = config.extended;
  f.fd = fd;
  f.len = len;
  return f;
}

bool frame_matches(const CanFrame& f, const highres::Config& config, std::uint32_t offset,
                   bool fd, std::uint8_t len) {
  const CanFrame expected = make_frame(config, offset, fd, len);
  return f.id == expected.id && f.extended == expected.extended && f.fd == fd && f.len == len;
}

highres::Decoded decode_payload(std::span<const std::uint8_t> p) {
  highres::Decoded d;
  d.gps_time_ns = static_cast<std::int64_t>(get_u64_le(p, 0));
  for (std::size_t i = 0; i < 3; ++i) {
    d.w_raw[i] = static_cast<std::int32_t>(get_u32_le(p, 8 + 4 * i));
    d.f_raw[i] = static_cast<std::int32_t>(get_u32_le(p, 20 + 4 * i));
    d.w_body_radps[i] = d.w_raw[i] * highres::kRateLsbRadps;
    d.f_body_mps2[i] = d.f_raw[i] * highres::kAccelLsbMps2;
  }
  d.sequence = get_u16_le(p, 32);
  d.flags = p[34];
  return d;
}

}  // namespace

// ---- SAE J1939 -----------------------------------------------------------------------------

namespace j1939 {

std::uint32_t make_id(std::uint8_t priority, std::uint32_t pgn, std::uint8_t source_address) {
  // SAE J1939-21: 3-bit priority, 18-bit PGN (EDP, DP, PF, PS), 8-bit source address.
  return (static_cast<std::uint32_t>(priority & 0x7u) << 26) | ((pgn & 0x3FFFFu) << 8) |
         source_address;
}

Raw16 encode_u16(double value, double resolution, double offset) {
  if (!std::isfinite(value)) return {kError16, FigureOfMerit::kError};
  const double scaled = std::round((value - offset) / resolution);
  if (scaled < 0.0) return {0, FigureOfMerit::kDegraded};
  if (scaled > static_cast<double>(kMaxValid16)) return {kMaxValid16, FigureOfMerit::kDegraded};
  return {static_cast<std::uint16_t>(scaled), FigureOfMerit::kFullyFunctional};
}

std::uint8_t encode_latency(double latency_s) {
  if (!std::isfinite(latency_s)) return kNotAvailable8;
  const double scaled = std::round(latency_s * 1000.0 / kLatencyResolutionMs);
  if (scaled < 0.0) return 0;
  if (scaled > static_cast<double>(kMaxValid8)) return kMaxValid8;
  return static_cast<std::uint8_t>(scaled);
}

CanFrame encode_ari(const ImuSample& sample, const Config& config) {
  // FRD body rates to J1939 pitch/roll/yaw (axis table in the header).
  const bool degraded = sample.truth_lost || sample.gyro_saturated;
  const auto rate = [&](std::size_t axis) {
    return with_flag(encode_u16(sample.w_body_radps[axis] * kRadToDeg, kRateResolutionDegps,
                                kRateOffsetDegps),
                     degraded);
  };
  return build_j1939(kPgnAri, config, {rate(1), rate(0), rate(2)},
                     encode_latency(sample.latency_s));
}

CanFrame encode_accs(const ImuSample& sample, const Config& config) {
  // FRD specific force to J1939 lateral (right), longitudinal (forward), vertical (up).
  const bool degraded = sample.truth_lost || sample.accel_saturated;
  const auto accel = [&](double value_mps2) {
    return with_flag(encode_u16(value_mps2, kAccelResolutionMps2, kAccelOffsetMps2), degraded);
  };
  return build_j1939(kPgnAccs, config,
                     {accel(sample.f_body_mps2[1]), accel(sample.f_body_mps2[0]),
                      accel(-sample.f_body_mps2[2])},
                     encode_latency(sample.latency_s));
}

}  // namespace j1939

// ---- navemu high-resolution layout ---------------------------------------------------------

namespace highres {

std::uint16_t crc16_ccitt_false(std::span<const std::uint8_t> bytes) {
  // Bitwise MSB-first CRC, poly 0x1021, init 0xFFFF (reveng catalogue: CRC-16/IBM-3740,
  // alias CRC-16/CCITT-FALSE).
  std::uint16_t crc = 0xFFFF;
  for (const std::uint8_t b : bytes) {
    crc = static_cast<std::uint16_t>(crc ^ (static_cast<unsigned>(b) << 8u));
    for (int i = 0; i < 8; ++i) {
      crc = (crc & 0x8000u) != 0 ? static_cast<std::uint16_t>((static_cast<unsigned>(crc) << 1u) ^ 0x1021u)
                                 : static_cast<std::uint16_t>(crc << 1);
    }
  }
  return crc;
}

std::array<CanFrame, kClassicFrameCount> encode_classic(const ImuSample& sample,
                                                        const Config& config) {
  const auto p = highres_payload(sample);
  const std::uint16_t crc = crc16_ccitt_false(p);
  std::array<CanFrame, kClassicFrameCount> frames{};
  for (std::uint32_t k = 0; k < 4; ++k) {
    frames[k] = make_frame(config, k, false, 8);
    for (std::size_t i = 0; i < 8; ++i) frames[k].data[i] = p[8 * k + i];
  }
  CanFrame& status = frames[kOffsetStatus];
  status = make_frame(config, kOffsetStatus, false, 8);
  for (std::size_t i = 0; i < 4; ++i) status.data[i] = p[32 + i];
  put_u16_le(status.data, 4, crc);
  return frames;
}

CanFrame encode_fd(const ImuSample& sample, const Config& config) {
  const auto p = highres_payload(sample);
  CanFrame frame = make_frame(config, kOffsetFd, true, 64);
  for (std::size_t i = 0; i < p.size(); ++i) frame.data[i] = p[i];
  put_u16_le(frame.data, kCrcInputSize, crc16_ccitt_false(p));
  return frame;
}

std::optional<Decoded> decode_classic(std::span<const CanFrame> frames, const Config& config) {
  if (frames.size() != kClassicFrameCount) return std::nullopt;
  std::array<std::uint8_t, kCrcInputSize> p{};
  for (std::uint32_t k = 0; k < kClassicFrameCount; ++k) {
    if (!frame_matches(frames[k], config, k, false, 8)) return std::nullopt;
  }
  for (std::size_t k = 0; k < 4; ++k) {
    for (std::size_t i = 0; i < 8; ++i) p[8 * k + i] = frames[k].data[i];
  }
  for (std::size_t i = 0; i < 4; ++i) p[32 + i] = frames[kOffsetStatus].data[i];
  if (crc16_ccitt_false(p) != get_u16_le(frames[kOffsetStatus].data, 4)) return std::nullopt;
  return decode_payload(p);
}

std::optional<Decoded> decode_fd(const CanFrame& frame, const Config& config) {
  if (!frame_matches(frame, config, kOffsetFd, true, 64)) return std::nullopt;
  const std::span<const std::uint8_t> p(frame.data.data(), kCrcInputSize);
  if (crc16_ccitt_false(p) != get_u16_le(frame.data, kCrcInputSize)) return std::nullopt;
  return decode_payload(p);
}

}  // namespace highres

}  // namespace navemu::can
