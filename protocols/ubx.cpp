// UBX framing, checksum, little-endian access and the incremental frame parser
// (UBX-13003221 section 32.2 "UBX Frame Structure", 32.3 "UBX Payload Definition Rules",
// 32.4 "UBX Checksum").
#include "protocols/ubx.hpp"

#include <bit>
#include <cstring>

namespace navemu::ubx {

// 8-bit Fletcher algorithm over class, id, length and payload (UBX-13003221 section 32.4).
std::array<std::uint8_t, 2> checksum(std::span<const std::uint8_t> bytes) {
  std::uint8_t a = 0, b = 0;
  for (const std::uint8_t x : bytes) {
    a = static_cast<std::uint8_t>(a + x);
    b = static_cast<std::uint8_t>(b + a);
  }
  return {a, b};
}

std::size_t begin_frame(std::uint8_t cls, std::uint8_t id, std::vector<std::uint8_t>& out) {
  const std::size_t start = out.size();
  out.push_back(kSync1);
  out.push_back(kSync2);
  out.push_back(cls);
  out.push_back(id);
  out.push_back(0);
  out.push_back(0);
  return start;
}

bool end_frame(std::size_t frame_start, std::vector<std::uint8_t>& out) {
  const std::size_t payload_size = out.size() - frame_start - 6;
  if (payload_size > kMaxWirePayload) {
    out.resize(frame_start);
    return false;
  }
  out[frame_start + 4] = static_cast<std::uint8_t>(payload_size & 0xFF);
  out[frame_start + 5] = static_cast<std::uint8_t>(payload_size >> 8);
  const auto ck =
      checksum(std::span<const std::uint8_t>(out).subspan(frame_start + 2, payload_size + 4));
  out.push_back(ck[0]);
  out.push_back(ck[1]);
  return true;
}

void append_frame(std::uint8_t cls, std::uint8_t id, std::span<const std::uint8_t> payload,
                  std::vector<std::uint8_t>& out) {
  if (payload.size() > kMaxWirePayload) return;
  const std::size_t start = begin_frame(cls, id, out);
  out.insert(out.end(), payload.begin(), payload.end());
  end_frame(start, out);
}

// ---- little-endian fields, IEEE 754 floats (UBX-13003221 section 32.3, number formats) ------

void Writer::u2(std::uint16_t v) {
  buf_.push_back(static_cast<std::uint8_t>(v & 0xFF));
  buf_.push_back(static_cast<std::uint8_t>(v >> 8));
}

void Writer::u4(std::uint32_t v) {
  for (int i = 0; i < 4; ++i) buf_.push_back(static_cast<std::uint8_t>((v >> (8 * i)) & 0xFF));
}

void Writer::r4(float v) { u4(std::bit_cast<std::uint32_t>(v)); }

void Writer::r8(double v) {
  const auto bits = std::bit_cast<std::uint64_t>(v);
  for (int i = 0; i < 8; ++i) buf_.push_back(static_cast<std::uint8_t>((bits >> (8 * i)) & 0xFF));
}

std::uint8_t Reader::u1(std::size_t off) const {
  if (off >= p_.size()) {
    ok_ = false;
    return 0;
  }
  return p_[off];
}

std::uint16_t Reader::u2(std::size_t off) const {
  if (off > p_.size() || p_.size() - off < 2) {
    ok_ = false;
    return 0;
  }
  return static_cast<std::uint16_t>(p_[off] | (p_[off + 1] << 8));
}

std::uint32_t Reader::u4(std::size_t off) const {
  if (off > p_.size() || p_.size() - off < 4) {
    ok_ = false;
    return 0;
  }
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(p_[off + i]) << (8 * i);
  return v;
}

float Reader::r4(std::size_t off) const { return std::bit_cast<float>(u4(off)); }

double Reader::r8(std::size_t off) const {
  if (off > p_.size() || p_.size() - off < 8) {
    ok_ = false;
    return 0.0;
  }
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(p_[off + i]) << (8 * i);
  return std::bit_cast<double>(v);
}

// ---- incremental parser --------------------------------------------------------------------
//
// The ring holds, from head_, the hist_ bytes of the candidate frame consumed so far (its first
// byte is the 0xB5 that started it) followed by the pend_ bytes not processed yet. A good frame
// removes its bytes; a failed candidate removes only its first byte, so that the rest become
// the front of the pending bytes and are scanned again. Capacity: at the start of a call the
// ring holds at most max_payload + 7 bytes (a frame in progress lacks at least its CK_B), one
// byte is added, and processing never adds bytes; hence max_payload + 8, plus some slack.

Parser::Parser(std::size_t max_payload)
    : max_payload_(max_payload), buf_(max_payload), ring_(max_payload + 16) {}

void Parser::reset() {
  state_ = State::kWaitSync1;
  head_ = hist_ = pend_ = 0;
  len_ = pos_ = 0;
}

Parser::Result Parser::feed(std::uint8_t byte) {
  if (hist_ + pend_ == ring_.size()) {
    // Unreachable by the bound above; kept so that a logic error cannot overrun the ring.
    counters_.junk_bytes += hist_ + pend_;
    reset();
  }
  ring_[(head_ + hist_ + pend_) % ring_.size()] = byte;
  ++pend_;
  return run();
}

Parser::Result Parser::poll() { return run(); }

Parser::Result Parser::run() {
  while (pend_ != 0) {
    const std::uint8_t b = ring_[(head_ + hist_) % ring_.size()];
    ++hist_;
    --pend_;
    const Result r = process(b);
    if (r != Result::kNeedMore) return r;
  }
  return Result::kNeedMore;
}

void Parser::accept_candidate() {
  head_ = (head_ + hist_) % ring_.size();
  hist_ = 0;
  state_ = State::kWaitSync1;
}

void Parser::drop_first() {
  // hist_ >= 1 here: the candidate's sync byte is in the ring.
  ++counters_.junk_bytes;
  head_ = (head_ + 1) % ring_.size();
  pend_ += hist_ - 1;
  hist_ = 0;
  state_ = State::kWaitSync1;
}

Parser::Result Parser::process(std::uint8_t byte) {
  const auto add_ck = [this](std::uint8_t v) {
    ck_a_ = static_cast<std::uint8_t>(ck_a_ + v);
    ck_b_ = static_cast<std::uint8_t>(ck_b_ + ck_a_);
  };
  switch (state_) {
    case State::kWaitSync1:
      if (byte == kSync1) {
        state_ = State::kWaitSync2;
      } else {
        ++counters_.junk_bytes;
        accept_candidate();  // the junk byte leaves the ring
      }
      return Result::kNeedMore;
    case State::kWaitSync2:
      if (byte == kSync2) {
        state_ = State::kClass;
        ck_a_ = ck_b_ = 0;
      } else {
        drop_first();  // this byte is scanned again (it may be a 0xB5)
      }
      return Result::kNeedMore;
    case State::kClass:
      cls_ = byte;
      add_ck(byte);
      state_ = State::kId;
      return Result::kNeedMore;
    case State::kId:
      id_ = byte;
      add_ck(byte);
      state_ = State::kLen1;
      return Result::kNeedMore;
    case State::kLen1:
      len_ = byte;
      add_ck(byte);
      state_ = State::kLen2;
      return Result::kNeedMore;
    case State::kLen2:
      len_ |= static_cast<std::size_t>(byte) << 8;
      add_ck(byte);
      if (len_ > max_payload_) {
        ++counters_.too_long;
        len_ = 0;
        drop_first();
        return Result::kTooLong;
      }
      pos_ = 0;
      state_ = len_ == 0 ? State::kCkA : State::kPayload;
      return Result::kNeedMore;
    case State::kPayload:
      buf_[pos_++] = byte;
      add_ck(byte);
      if (pos_ == len_) state_ = State::kCkA;
      return Result::kNeedMore;
    case State::kCkA:
      rx_ck_a_ = byte;
      state_ = State::kCkB;
      return Result::kNeedMore;
    case State::kCkB:
      if (rx_ck_a_ == ck_a_ && byte == ck_b_) {
        ++counters_.frames;
        accept_candidate();
        return Result::kFrame;
      }
      ++counters_.checksum_errors;
      drop_first();
      return Result::kChecksumError;
  }
  return Result::kNeedMore;
}

}  // namespace navemu::ubx
