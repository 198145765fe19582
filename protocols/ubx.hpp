#pragma once
// u-blox UBX protocol: framing, checksum, little-endian field access and an incremental frame
// parser (u-blox 8 / M8 Receiver Description incl. Protocol Specification, UBX-13003221,
// section 32.2 "UBX Frame Structure" and 32.4 "UBX Checksum").
//
// Frame: 0xB5 0x62, class, id, length (u16 LE), payload, CK_A, CK_B, where CK_A/CK_B is the
// 8-bit Fletcher checksum over class, id, length and payload.

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace navemu::ubx {

inline constexpr std::uint8_t kSync1 = 0xB5;
inline constexpr std::uint8_t kSync2 = 0x62;

// The Fletcher checksum (CK_A, CK_B) over `bytes` (class, id, length and payload).
std::array<std::uint8_t, 2> checksum(std::span<const std::uint8_t> bytes);

// Largest payload a frame can carry (16-bit length field).
inline constexpr std::size_t kMaxWirePayload = 0xFFFF;
// Bytes a frame adds around its payload: sync (2), class, id, length (2), checksum (2).
inline constexpr std::size_t kFrameOverhead = 8;

// Appends a complete frame to `out`. A payload above kMaxWirePayload cannot be framed: nothing
// is appended then.
void append_frame(std::uint8_t cls, std::uint8_t id, std::span<const std::uint8_t> payload,
                  std::vector<std::uint8_t>& out);

// Building a frame in place, for encoders that write the payload straight into `out`:
// begin_frame() appends sync, class, id and a placeholder length and returns the frame's
// offset in `out`; the payload is then appended (e.g. with a Writer); end_frame() patches the
// length and appends the checksum. A payload above kMaxWirePayload is removed again and
// end_frame() returns false.
std::size_t begin_frame(std::uint8_t cls, std::uint8_t id, std::vector<std::uint8_t>& out);
bool end_frame(std::size_t frame_start, std::vector<std::uint8_t>& out);

// Little-endian payload writer: fields are appended in order (IEEE 754 for R4/R8).
class Writer {
 public:
  explicit Writer(std::vector<std::uint8_t>& buf) : buf_(buf) {}
  void u1(std::uint8_t v) { buf_.push_back(v); }
  void i1(std::int8_t v) { u1(static_cast<std::uint8_t>(v)); }
  void u2(std::uint16_t v);
  void i2(std::int16_t v) { u2(static_cast<std::uint16_t>(v)); }
  void u4(std::uint32_t v);
  void i4(std::int32_t v) { u4(static_cast<std::uint32_t>(v)); }
  void r4(float v);
  void r8(double v);
  void zeros(std::size_t n) { buf_.insert(buf_.end(), n, 0); }
  void bytes(std::span<const std::uint8_t> b) { buf_.insert(buf_.end(), b.begin(), b.end()); }
  std::size_t size() const { return buf_.size(); }

 private:
  std::vector<std::uint8_t>& buf_;
};

// Bounds-checked little-endian reader at byte offsets of a payload; reads past the end give 0
// and set ok() false (callers check the length first; this is the safety net).
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> p) : p_(p) {}
  std::uint8_t u1(std::size_t off) const;
  std::int8_t i1(std::size_t off) const { return static_cast<std::int8_t>(u1(off)); }
  std::uint16_t u2(std::size_t off) const;
  std::int16_t i2(std::size_t off) const { return static_cast<std::int16_t>(u2(off)); }
  std::uint32_t u4(std::size_t off) const;
  std::int32_t i4(std::size_t off) const { return static_cast<std::int32_t>(u4(off)); }
  float r4(std::size_t off) const;
  double r8(std::size_t off) const;
  std::size_t size() const { return p_.size(); }
  bool ok() const { return ok_; }

 private:
  std::span<const std::uint8_t> p_;
  mutable bool ok_ = true;
};

// Incremental frame parser: feed bytes one at a time (or a span); it resynchronises on junk,
// interleaved NMEA and partial frames, and never allocates after construction.
//
// Resynchronisation: when a candidate frame fails (second sync byte missing, length above
// max_payload, or checksum wrong) only its first sync byte is discarded; every byte after it is
// scanned again, so a frame that starts inside the bytes of a false or truncated one is still
// found (e.g. a frame cut short by a reset followed by a complete one: the length of the cut
// frame swallows the next frame's bytes, its checksum fails, and the replay then finds the
// complete frame). The bytes of the current candidate and the ones still to be replayed are
// kept in one ring of max_payload + 16 bytes allocated at construction; the stream suffix they
// form never exceeds max_payload + 8 bytes.
//
// One call returns at most one result. A replay can hold more than one frame, so after feed()
// returned something other than kNeedMore, bytes may still be pending: call poll() until it
// returns kNeedMore (or use the span overload of feed(), which does that). Pending bytes are
// otherwise processed, in order, before the next byte fed.
//
// Cost: each byte is scanned once, plus once per false candidate it lies in; adversarial input
// with a false sync every few bytes and huge plausible lengths costs up to max_payload scans
// per byte.
class Parser {
 public:
  enum class Result {
    kNeedMore,       // inside a frame, or skipping bytes that are not a frame
    kFrame,          // a complete frame with a good checksum: see cls(), id(), payload()
    kChecksumError,  // a complete frame whose checksum is wrong (dropped)
    kTooLong,        // a length above max_payload (dropped; the parser resynchronises)
  };
  explicit Parser(std::size_t max_payload = 4096);

  // Appends `byte` to the input and processes pending input up to the first result.
  Result feed(std::uint8_t byte);
  // Processes pending input (bytes being replayed) up to the first result; kNeedMore when none
  // is left.
  Result poll();
  // True while replayed bytes wait to be processed.
  bool pending() const { return pend_ != 0; }
  // Bytes held: those of an unfinished candidate frame and those waiting to be replayed (at
  // the end of a capture: a frame cut short).
  std::size_t buffered() const { return hist_ + pend_; }

  // Feeds `bytes` and calls on_result(Result) for every result other than kNeedMore, including
  // those found in replayed bytes; no input is left pending on return. cls(), id() and
  // payload() are valid inside the callback for kFrame.
  template <typename OnResult>
  void feed(std::span<const std::uint8_t> bytes, OnResult&& on_result) {
    for (const std::uint8_t b : bytes) {
      for (Result r = feed(b); r != Result::kNeedMore; r = poll()) on_result(r);
    }
  }

  // Forgets the frame in progress and any pending bytes (counters are kept).
  void reset();

  std::uint8_t cls() const { return cls_; }
  std::uint8_t id() const { return id_; }
  // Valid until the next call of feed(), poll() or reset().
  std::span<const std::uint8_t> payload() const { return {buf_.data(), len_}; }

  // junk_bytes counts every byte dropped outside a good frame (each byte once), so at any time
  // sum over good frames of (payload size + 8) + junk_bytes + buffered() == bytes fed.
  struct Counters {
    std::uint64_t frames = 0, checksum_errors = 0, too_long = 0, junk_bytes = 0;
  };
  const Counters& counters() const { return counters_; }

 private:
  enum class State { kWaitSync1, kWaitSync2, kClass, kId, kLen1, kLen2, kPayload, kCkA, kCkB };
  Result run();
  Result process(std::uint8_t byte);
  void accept_candidate();  // a good frame: its bytes leave the ring
  void drop_first();        // a failed candidate: drop its first byte, replay the rest

  State state_ = State::kWaitSync1;
  std::size_t max_payload_;
  std::vector<std::uint8_t> buf_;   // payload of the frame in progress
  std::vector<std::uint8_t> ring_;  // candidate bytes (from head_) then pending bytes
  std::size_t head_ = 0, hist_ = 0, pend_ = 0;
  std::uint8_t cls_ = 0, id_ = 0, ck_a_ = 0, ck_b_ = 0, rx_ck_a_ = 0;
  std::size_t len_ = 0, pos_ = 0;
  Counters counters_;
};

}  // namespace navemu::ubx
