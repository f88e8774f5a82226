// Decoder: a DBC database compiled into flat tables for decoding and encoding frames.
//
// Lookup: standard ids index a 2048-entry table directly, extended ids an open-addressing hash
// table (Fibonacci hash, linear probing, at most half full); no allocation per frame. Each
// signal is compiled to (first byte, bytes spanned, shift, mask): Intel assembles the spanned
// bytes little-endian and shifts right by start_bit % 8; Motorola converts the MSB start bit to
// the big-endian linear position msb = 8*(start/8) + 7 - start%8, assembles the bytes
// big-endian and shifts right by 7 - (msb + length - 1) % 8. Then
//     raw = sign_extend(bits, length)  (or IEEE float32/float64 reinterpretation)
//     physical = raw * factor + offset
// decode() of a message of at most 8 bytes without multiplexing, whose signals are integers
// shorter than 64 bits, reads the payload once as one little- and one big-endian 64-bit word and
// gets each signal with three shifts from a 24-byte table entry (Decoder::WordSignal).
// The encoder does the inverse: raw = round((physical - offset) / factor), clamped to what the
// bit width holds (unsigned [0, 2^n - 1], signed [-2^(n-1), 2^(n-1) - 1]).
//
// Multiplexing: signals are visited switches first; a signal whose multiplexor switch is absent
// or holds a raw value outside the signal's ranges is not present and is not reported.
// A frame shorter than the DBC length is rejected (kTooShort), never zero-filled.
//
// For a mapping layer: resolve (message, signal) names to a SignalRef once, collect them in a
// SignalSelection, and decode each frame into a small array of slot values (no strings, no
// allocation per frame).
//
// Thread-safety: a Decoder is immutable after compile(); all const methods may be called from
// several threads at once. DecodeStats and SignalSelection belong to their caller.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vmass/can/can_frame.hpp"
#include "vmass/can/dbc.hpp"

namespace vmass::can {

/// A signal of a message, by indices into Decoder::database().
struct SignalRef {
  int message = -1;
  int signal = -1;
  bool valid() const { return message >= 0 && signal >= 0; }
};

enum class DecodeStatus : std::uint8_t {
  kOk,          ///< decoded; present signals reported
  kUnknownId,   ///< no message with this id (and id type) in the DBC
  kTooShort,    ///< payload shorter than the DBC length: rejected
  kRemote,      ///< remote request: no payload to decode
  kErrorFrame,  ///< error frame: not a message
};

std::string_view decode_status_name(DecodeStatus status);

/// Counters a caller keeps over many decode() calls.
struct DecodeStats {
  std::uint64_t frames = 0;
  std::uint64_t decoded = 0;
  std::uint64_t unknown_id = 0;
  std::uint64_t too_short = 0;
  std::uint64_t remote = 0;
  std::uint64_t error_frames = 0;
  void count(DecodeStatus status);
};

/// One signal compiled for extraction (see the header comment for the arithmetic).
struct CompiledSignal {
  std::uint64_t mask = 0;      ///< low `length` bits set
  std::uint64_t sign_bit = 0;  ///< 1 << (length - 1) for signed signals, 0 for unsigned
  double factor = 1.0;
  double offset = 0.0;
  std::uint8_t first_byte = 0;  ///< Intel: least significant byte; Motorola: most significant
  std::uint8_t byte_count = 0;  ///< bytes spanned, 1..9
  std::uint8_t shift = 0;       ///< right shift after assembling the bytes
  std::uint8_t length = 0;      ///< bits, 1..64
  std::uint8_t word_shift = 0;  ///< fast path: right shift of the 8-byte word (see extract_raw)
  bool fast = false;            ///< fast path: byte_count <= 8 and 8 bytes readable at first_byte
  bool is_signed = false;
  ByteOrder byte_order = ByteOrder::kIntel;
  ValueType value_type = ValueType::kInteger;
  std::int8_t switch_slot = -1;   ///< for a multiplexor: its slot among the message's switches
  std::int16_t mux_parent = -1;   ///< signal index (in its message) of the switch, -1 if none
  std::uint16_t range_begin = 0;  ///< into the decoder's range table
  std::uint16_t range_count = 0;
};

class Decoder {
 public:
  /// Most multiplexor switches in one message.
  static constexpr int kMaxSwitches = 16;

  /// Compiles a database (normally from a parse without errors). Fails, with a message naming
  /// the message or signal, on layouts the tables cannot hold (a signal beyond its payload,
  /// length not 1..64, too many switches).
  static std::optional<Decoder> compile(Database database, std::string* error = nullptr);

  const Database& database() const { return db_; }
  int message_count() const { return static_cast<int>(db_.messages.size()); }

  /// Message index for an identifier (no flag bits), or -1.
  int find_message(std::uint32_t id, bool extended) const {
    if (!extended) return id <= kSffMask ? standard_[id] : -1;
    return find_extended(id);
  }
  int find_message(std::string_view name) const { return db_.find_message(name); }
  /// Resolves names once; invalid SignalRef when either is unknown.
  SignalRef find_signal(std::string_view message, std::string_view signal) const;

  /// Finds the frame's message and says whether its payload can be decoded (kOk), without
  /// decoding anything.
  DecodeStatus classify(const CanFrame& frame, int* message_index) const;

  /// Decodes a frame: calls sink(int signal_index, double physical) for every present signal of
  /// its message, switches before the signals they select. `message_index` receives the message
  /// (or -1). Allocates nothing.
  template <class Sink>
  DecodeStatus decode(const CanFrame& frame, Sink&& sink, int* message_index = nullptr) const;

  /// Decodes a frame into values[signal index]; present[i] is set to 1 for present signals and
  /// 0 for the others. Both arrays must hold the message's signal count (at most
  /// max_signals_per_message()).
  DecodeStatus decode_into(const CanFrame& frame, int* message_index, double* values,
                           std::uint8_t* present) const;

  /// One signal's physical value from a frame of its message; false when the frame is too short
  /// or the signal is not selected by its multiplexor.
  bool signal_value(const CanFrame& frame, SignalRef ref, double* physical) const;

  /// Raw (sign-extended) bits of a signal from a payload of sufficient length.
  std::int64_t extract_raw(const CompiledSignal& s, const std::uint8_t* data) const;
  /// Physical value of a signal from a payload of sufficient length.
  double extract_physical(const CompiledSignal& s, const std::uint8_t* data) const;

  /// Encodes a message: id, flags, length from the DBC; every signal whose multiplexor chain
  /// selects it is written from values[signal index] (switches first), the others left 0.
  /// Returns false for an invalid message index.
  bool encode(int message_index, const double* values, CanFrame* frame) const;
  /// Writes one signal's physical value into a payload (rounding, clamping to the bit width).
  void encode_signal(SignalRef ref, double physical, std::uint8_t* data) const;
  /// physical -> raw bits (low `length` bits), with rounding and clamping.
  std::uint64_t physical_to_raw(const CompiledSignal& s, double physical) const;

  const CompiledSignal& compiled(SignalRef ref) const {
    return signals_[static_cast<std::size_t>(
                        messages_[static_cast<std::size_t>(ref.message)].signal_begin) +
                    static_cast<std::size_t>(ref.signal)];
  }
  int max_signals_per_message() const { return max_signals_; }

 private:
  struct CompiledMessage {
    std::uint32_t signal_begin = 0;
    std::uint32_t signal_count = 0;
    std::uint32_t order_begin = 0;  ///< into order_: signal indices, switches first
    std::uint8_t length = 0;
    std::uint8_t switch_count = 0;
    bool frame_word = false;  ///< no switch, length <= 8, every signal has a WordSignal
  };
  /// A signal of a message decoded from the frame word (decode()'s path for messages of up to
  /// 8 bytes without multiplexing whose signals are integers shorter than 64 bits): with w the
  /// payload's first 8 bytes read little-endian (Intel) or big-endian (Motorola, byte 0 on top),
  ///     x = (w << to_top) >> unsigned_shift           (logical; puts the field's MSB on top,
  ///     raw = int64(x) >> (64 - length - unsigned_shift)  or below it for unsigned fields)
  /// which sign-extends signed fields and zero-extends unsigned ones without a branch. 24 bytes
  /// (CompiledSignal has 56), so that decoding touches fewer cache lines.
  struct WordSignal {
    double factor = 1.0;
    double offset = 0.0;
    std::uint8_t word = 0;            ///< 0: little-endian, 1: big-endian
    std::uint8_t to_top = 0;          ///< 63 - the field's MSB position in the word
    std::uint8_t unsigned_shift = 0;  ///< 1 for unsigned fields, 0 for signed
    std::uint8_t down = 0;            ///< 64 - length - unsigned_shift
  };

  Decoder() = default;
  // compile()'s steps; each returns "" or why the database cannot be compiled.
  std::string compile_message(std::size_t message_index);
  std::string compile_signal_of(const Message& m, const Signal& sg, int* switches, bool* word_path);
  std::string index_extended_ids();
  int find_extended(std::uint32_t id) const;
  bool in_ranges(const CompiledSignal& s, std::uint64_t switch_raw) const;

  Database db_;
  std::vector<CompiledMessage> messages_;
  std::vector<CompiledSignal> signals_;
  std::vector<WordSignal> word_signals_;  ///< parallel to signals_ (used where frame_word)
  std::vector<std::uint16_t> order_;
  std::vector<MuxRange> ranges_;
  std::array<std::int16_t, kSffMask + 1> standard_{};
  std::vector<std::pair<std::uint32_t, int>> extended_;  ///< sorted by id
  /// Open-addressing table of the extended ids (power-of-two size, at most half full; empty
  /// slots hold message -1): Fibonacci hash, linear probing.
  std::vector<std::pair<std::uint32_t, int>> extended_hash_;
  unsigned extended_hash_bits_ = 0;
  int max_signals_ = 0;
};

/// A set of (message, signal) pairs resolved once; decode() reports each selected signal
/// present in a frame by its slot number (the order of add()). No allocation per frame.
class SignalSelection {
 public:
  explicit SignalSelection(const Decoder& decoder);
  /// Adds a signal; returns its slot, or -1 for an invalid ref.
  int add(SignalRef ref);
  int size() const { return static_cast<int>(slots_.size()); }
  SignalRef ref(int slot) const { return slots_[static_cast<std::size_t>(slot)]; }

  /// Calls on_value(int slot, double physical) for each selected signal present in the frame.
  template <class OnValue>
  DecodeStatus decode(const CanFrame& frame, OnValue&& on_value) const;
  /// As decode(), for a frame that Decoder::classify() found to be of message m (kOk).
  template <class OnValue>
  void decode_message(int m, const CanFrame& frame, OnValue&& on_value) const;

 private:
  struct Entry {
    int signal = 0;
    int slot = 0;
  };
  const Decoder* decoder_;
  std::vector<SignalRef> slots_;
  std::vector<std::vector<Entry>> by_message_;
};

// ------------------------------------------------------------------ inline implementation

inline std::int64_t Decoder::extract_raw(const CompiledSignal& s, const std::uint8_t* data) const {
  const std::uint8_t* p = data + s.first_byte;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  if (s.fast) {
    // One unaligned 8-byte load: Intel shifts it right by start % 8; Motorola byte-swaps it,
    // which puts the first byte on top, and shifts by 8 * (8 - byte_count) + (7 - lsb % 8).
    // Sign extension without a branch: (x ^ s) - s with s the sign bit (0 when unsigned).
    std::uint64_t w;
    __builtin_memcpy(&w, p, sizeof w);
    if (s.byte_order == ByteOrder::kMotorola) w = __builtin_bswap64(w);
    const std::uint64_t bits = (w >> s.word_shift) & s.mask;
    return static_cast<std::int64_t>((bits ^ s.sign_bit) - s.sign_bit);
  }
#endif
  const int n = s.byte_count < 8 ? s.byte_count : 8;
  std::uint64_t bits = 0;
  if (s.byte_order == ByteOrder::kIntel) {
    for (int i = n - 1; i >= 0; --i) bits = (bits << 8) | p[i];
    bits >>= s.shift;
    if (s.byte_count == 9) bits |= static_cast<std::uint64_t>(p[8]) << (64 - s.shift);
  } else {
    for (int i = 0; i < n; ++i) bits = (bits << 8) | p[i];
    if (s.byte_count == 9) {
      bits = (bits << (8 - s.shift)) | (static_cast<std::uint64_t>(p[8]) >> s.shift);
    } else {
      bits >>= s.shift;
    }
  }
  bits &= s.mask;
  if (s.is_signed && s.length < 64 && (bits >> (s.length - 1)) != 0) bits |= ~s.mask;
  return static_cast<std::int64_t>(bits);
}

inline double Decoder::extract_physical(const CompiledSignal& s, const std::uint8_t* data) const {
  const std::int64_t raw = extract_raw(s, data);
  double v;
  if (s.value_type == ValueType::kInteger) {
    // Below 64 bits an unsigned raw value is a non-negative int64: one conversion instruction.
    v = (s.is_signed || s.length < 64) ? static_cast<double>(raw)
                                       : static_cast<double>(static_cast<std::uint64_t>(raw));
  } else if (s.value_type == ValueType::kFloat32) {
    const auto u = static_cast<std::uint32_t>(raw);
    float f;
    static_assert(sizeof f == sizeof u, "float32");
    __builtin_memcpy(&f, &u, sizeof f);
    v = static_cast<double>(f);
  } else {
    const auto u = static_cast<std::uint64_t>(raw);
    __builtin_memcpy(&v, &u, sizeof v);
  }
  return v * s.factor + s.offset;
}

inline bool Decoder::in_ranges(const CompiledSignal& s, std::uint64_t switch_raw) const {
  for (std::uint16_t i = 0; i < s.range_count; ++i) {
    const MuxRange& r = ranges_[s.range_begin + i];
    if (switch_raw >= r.lo && switch_raw <= r.hi) return true;
  }
  return false;
}

inline DecodeStatus Decoder::classify(const CanFrame& frame, int* message_index) const {
  if (message_index) *message_index = -1;
  if (frame.error()) return DecodeStatus::kErrorFrame;
  const int m = find_message(frame.id, frame.extended());
  if (message_index) *message_index = m;
  if (m < 0) return DecodeStatus::kUnknownId;
  if (frame.remote()) return DecodeStatus::kRemote;
  if (frame.len < messages_[static_cast<std::size_t>(m)].length) return DecodeStatus::kTooShort;
  return DecodeStatus::kOk;
}

template <class Sink>
DecodeStatus Decoder::decode(const CanFrame& frame, Sink&& sink, int* message_index) const {
  int m = -1;
  const DecodeStatus st = classify(frame, &m);
  if (message_index) *message_index = m;
  if (st != DecodeStatus::kOk) return st;
  const CompiledMessage& cm = messages_[static_cast<std::size_t>(m)];
  const CompiledSignal* sig = signals_.data() + cm.signal_begin;
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
  if (cm.frame_word) {
    // Classic frames: the payload's first 8 bytes in both byte orders, read once per frame;
    // each signal is then three shifts (see WordSignal) and one conversion.
    std::uint64_t words[2];
    __builtin_memcpy(&words[0], frame.data, sizeof words[0]);
    words[1] = __builtin_bswap64(words[0]);
    const WordSignal* ws = word_signals_.data() + cm.signal_begin;
    const int count = static_cast<int>(cm.signal_count);  // <= 0xFFFF (compile() checks)
    for (int i = 0; i < count; ++i) {
      const WordSignal& s = ws[i];
      const std::uint64_t x = (words[s.word] << s.to_top) >> s.unsigned_shift;
      const std::int64_t raw = static_cast<std::int64_t>(x) >> s.down;
      sink(i, static_cast<double>(raw) * s.factor + s.offset);
    }
    return DecodeStatus::kOk;
  }
#endif
  if (cm.switch_count == 0) {  // no multiplexing: every signal, in DBC order
    for (std::uint32_t i = 0; i < cm.signal_count; ++i) {
      sink(static_cast<int>(i), extract_physical(sig[i], frame.data));
    }
    return DecodeStatus::kOk;
  }
  const std::uint16_t* order = order_.data() + cm.order_begin;
  std::uint64_t switch_raw[kMaxSwitches];
  std::uint32_t switch_present = 0;  // bit per switch slot
  for (std::uint32_t k = 0; k < cm.signal_count; ++k) {
    const int i = order[k];
    const CompiledSignal& s = sig[i];
    if (s.mux_parent >= 0) {
      const CompiledSignal& parent = sig[s.mux_parent];
      if ((switch_present & (1u << parent.switch_slot)) == 0 ||
          !in_ranges(s, switch_raw[parent.switch_slot])) {
        continue;
      }
    }
    if (s.switch_slot >= 0) {
      switch_raw[s.switch_slot] = static_cast<std::uint64_t>(extract_raw(s, frame.data)) & s.mask;
      switch_present |= 1u << s.switch_slot;
    }
    sink(i, extract_physical(s, frame.data));
  }
  return DecodeStatus::kOk;
}

template <class OnValue>
DecodeStatus SignalSelection::decode(const CanFrame& frame, OnValue&& on_value) const {
  int m = -1;
  const DecodeStatus st = decoder_->classify(frame, &m);
  if (st != DecodeStatus::kOk) return st;
  decode_message(m, frame, on_value);
  return DecodeStatus::kOk;
}

template <class OnValue>
void SignalSelection::decode_message(int m, const CanFrame& frame, OnValue&& on_value) const {
  double value = 0.0;
  for (const Entry& e : by_message_[static_cast<std::size_t>(m)]) {
    if (decoder_->signal_value(frame, SignalRef{m, e.signal}, &value)) on_value(e.slot, value);
  }
}

}  // namespace vmass::can
