// Decoder: compiling a Database into flat tables, and encoding (see decoder.hpp).
#include "vmass/can/decoder.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace vmass::can {

std::string_view decode_status_name(DecodeStatus status) {
  switch (status) {
    case DecodeStatus::kOk:
      return "ok";
    case DecodeStatus::kUnknownId:
      return "unknown id";
    case DecodeStatus::kTooShort:
      return "shorter than the DBC length";
    case DecodeStatus::kRemote:
      return "remote request";
    case DecodeStatus::kErrorFrame:
      return "error frame";
  }
  return "?";
}

void DecodeStats::count(DecodeStatus status) {
  ++frames;
  switch (status) {
    case DecodeStatus::kOk:
      ++decoded;
      break;
    case DecodeStatus::kUnknownId:
      ++unknown_id;
      break;
    case DecodeStatus::kTooShort:
      ++too_short;
      break;
    case DecodeStatus::kRemote:
      ++remote;
      break;
    case DecodeStatus::kErrorFrame:
      ++error_frames;
      break;
  }
}

namespace {

// The frame-word form of a signal (Decoder::WordSignal), or false when it has none (a float,
// 64 bits, or bits beyond byte 7). Bit b of the little-endian word is bit b % 8 of byte b / 8
// (Intel); the big-endian word holds byte 0 on top, so linear position p is bit 63 - p.
template <class WordSignal>
bool word_signal(const Signal& sg, WordSignal& out) {
  if (sg.value_type != ValueType::kInteger || sg.length < 1 || sg.length >= 64) return false;
  int msb = 0;  // position of the field's most significant bit in the word
  if (sg.byte_order == ByteOrder::kIntel) {
    msb = sg.start_bit + sg.length - 1;
  } else {
    const int first_linear = (sg.start_bit / 8) * 8 + (7 - sg.start_bit % 8);
    if (first_linear + sg.length - 1 > 63) return false;
    msb = 63 - first_linear;
  }
  if (sg.start_bit < 0 || msb > 63 || msb - (sg.length - 1) < 0) return false;
  out.factor = sg.factor;
  out.offset = sg.offset;
  out.word = sg.byte_order == ByteOrder::kIntel ? 0 : 1;
  out.to_top = static_cast<std::uint8_t>(63 - msb);
  out.unsigned_shift = sg.is_signed ? 0 : 1;
  out.down = static_cast<std::uint8_t>(64 - sg.length - out.unsigned_shift);
  return true;
}

bool compile_signal(const Signal& sg, int length_bytes, CompiledSignal& out, std::string& why) {
  if (sg.length < 1 || sg.length > 64) {
    why = "length " + std::to_string(sg.length) + " is not 1..64 bits";
    return false;
  }
  if ((sg.value_type == ValueType::kFloat32 && sg.length != 32) ||
      (sg.value_type == ValueType::kFloat64 && sg.length != 64)) {
    why = "float value type with length " + std::to_string(sg.length);
    return false;
  }
  int first_bit = 0, last_bit = 0;  // linear positions in the layout's numbering
  if (sg.byte_order == ByteOrder::kIntel) {
    first_bit = sg.start_bit;
    last_bit = sg.start_bit + sg.length - 1;
    out.shift = static_cast<std::uint8_t>(sg.start_bit % 8);
  } else {
    first_bit = (sg.start_bit / 8) * 8 + (7 - sg.start_bit % 8);  // MSB, big-endian linear
    last_bit = first_bit + sg.length - 1;                         // LSB
    out.shift = static_cast<std::uint8_t>(7 - last_bit % 8);
  }
  if (sg.start_bit < 0 || last_bit >= 8 * length_bytes) {
    why = "bits do not fit in the " + std::to_string(length_bytes) + "-byte payload";
    return false;
  }
  out.first_byte = static_cast<std::uint8_t>(first_bit / 8);
  out.byte_count = static_cast<std::uint8_t>(last_bit / 8 - first_bit / 8 + 1);
  out.length = static_cast<std::uint8_t>(sg.length);
  // Every CanFrame holds 64 data bytes, so an 8-byte load at first_byte is in bounds when
  // first_byte <= 56; bytes past the frame's length are masked or shifted away.
  out.fast = out.byte_count <= 8 && out.first_byte + 8 <= kFdMaxLen;
  out.word_shift = static_cast<std::uint8_t>(
      sg.byte_order == ByteOrder::kIntel ? out.shift : 8 * (8 - out.byte_count) + out.shift);
  out.mask = sg.length == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << sg.length) - 1;
  out.is_signed = sg.is_signed;
  out.sign_bit = sg.is_signed ? std::uint64_t{1} << (sg.length - 1) : 0;
  out.byte_order = sg.byte_order;
  out.value_type = sg.value_type;
  out.factor = sg.factor;
  out.offset = sg.offset;
  return true;
}

}  // namespace

namespace {

/// Visiting order of a message's signals: by depth in the multiplexor tree (switches before
/// what they select), DBC order within a depth. "" or why the tree is not one.
std::string visiting_order(const Message& m, std::vector<std::uint16_t>* order) {
  std::vector<int> depth(m.signals.size(), 0);
  for (std::size_t i = 0; i < m.signals.size(); ++i) {
    int p = m.signals[i].mux_parent;
    while (p >= 0 && depth[i] <= static_cast<int>(m.signals.size())) {
      ++depth[i];
      p = m.signals[static_cast<std::size_t>(p)].mux_parent;
    }
    if (p >= 0) return "signal " + m.signals[i].name + ": multiplexor chain loops";
  }
  order->resize(m.signals.size());
  for (std::size_t i = 0; i < order->size(); ++i) (*order)[i] = static_cast<std::uint16_t>(i);
  std::stable_sort(order->begin(), order->end(),
                   [&](std::uint16_t a, std::uint16_t b) { return depth[a] < depth[b]; });
  return "";
}

}  // namespace

std::string Decoder::compile_signal_of(const Message& m, const Signal& sg, int* switches,
                                       bool* word_path) {
  CompiledSignal cs;
  std::string why;
  if (!compile_signal(sg, m.length, cs, why)) {
    return "signal " + sg.name + " of message " + m.name + ": " + why;
  }
  if (sg.is_multiplexor) {
    if (*switches >= kMaxSwitches)
      return "message " + m.name + " has more than 16 multiplexor switches";
    cs.switch_slot = static_cast<std::int8_t>((*switches)++);
  }
  if (sg.mux_parent >= 0) {
    if (static_cast<std::size_t>(sg.mux_parent) >= m.signals.size() ||
        !m.signals[static_cast<std::size_t>(sg.mux_parent)].is_multiplexor) {
      return "signal " + sg.name + " of message " + m.name + ": its multiplexor is not a switch";
    }
    if (sg.mux_ranges.empty()) {
      return "signal " + sg.name + " of message " + m.name + ": no multiplexor value";
    }
    cs.mux_parent = static_cast<std::int16_t>(sg.mux_parent);
    cs.range_begin = static_cast<std::uint16_t>(ranges_.size());
    cs.range_count = static_cast<std::uint16_t>(sg.mux_ranges.size());
    ranges_.insert(ranges_.end(), sg.mux_ranges.begin(), sg.mux_ranges.end());
    if (ranges_.size() > 0xFFFF) return "too many multiplexor ranges";
  }
  WordSignal ws;
  if (!word_signal(sg, ws)) *word_path = false;
  signals_.push_back(cs);
  word_signals_.push_back(ws);
  return "";
}

std::string Decoder::compile_message(std::size_t mi) {
  const Message& m = db_.messages[mi];
  if (m.length < 0 || m.length > kFdMaxLen) {
    return "message " + m.name + ": length " + std::to_string(m.length);
  }
  if (m.signals.size() > 0xFFFF) return "message " + m.name + ": too many signals";
  CompiledMessage cm;
  cm.signal_begin = static_cast<std::uint32_t>(signals_.size());
  cm.signal_count = static_cast<std::uint32_t>(m.signals.size());
  cm.order_begin = static_cast<std::uint32_t>(order_.size());
  cm.length = static_cast<std::uint8_t>(m.length);
  int switches = 0;
  bool word_path = m.length <= kClassicMaxLen;
  for (const Signal& sg : m.signals) {
    if (std::string e = compile_signal_of(m, sg, &switches, &word_path); !e.empty()) return e;
  }
  cm.switch_count = static_cast<std::uint8_t>(switches);
  cm.frame_word = switches == 0 && word_path;
  std::vector<std::uint16_t> order;
  if (std::string e = visiting_order(m, &order); !e.empty()) return e;
  order_.insert(order_.end(), order.begin(), order.end());
  messages_.push_back(cm);
  max_signals_ = std::max(max_signals_, static_cast<int>(m.signals.size()));
  if (m.extended) {
    extended_.emplace_back(m.id, static_cast<int>(mi));
  } else if (m.id <= kSffMask) {
    if (standard_[m.id] >= 0) return "message " + m.name + ": duplicate id";
    standard_[m.id] = static_cast<std::int16_t>(mi);
  } else {
    return "message " + m.name + ": standard id above 0x7FF";
  }
  return "";
}

std::string Decoder::index_extended_ids() {
  std::sort(extended_.begin(), extended_.end());
  for (std::size_t i = 1; i < extended_.size(); ++i) {
    if (extended_[i].first == extended_[i - 1].first) {
      return "message " + db_.messages[static_cast<std::size_t>(extended_[i].second)].name +
             ": duplicate extended id";
    }
  }
  // Open addressing, at most half full: a lookup ends at the id or at an empty slot.
  unsigned bits = 1;
  while ((std::size_t{1} << bits) < 2 * extended_.size()) ++bits;
  extended_hash_bits_ = bits;
  extended_hash_.assign(std::size_t{1} << bits, {0u, -1});
  for (const auto& [id, index] : extended_) {
    std::size_t slot = (id * 2654435769u) >> (32 - bits);
    while (extended_hash_[slot].second >= 0) slot = (slot + 1) & (extended_hash_.size() - 1);
    extended_hash_[slot] = {id, index};
  }
  return "";
}

std::optional<Decoder> Decoder::compile(Database database, std::string* error) {
  Decoder d;
  d.db_ = std::move(database);
  d.standard_.fill(-1);
  std::string why;
  for (std::size_t mi = 0; mi < d.db_.messages.size() && why.empty(); ++mi) {
    why = d.compile_message(mi);
  }
  if (why.empty() && d.db_.messages.size() > 0x7FFF) why = "too many messages";
  if (why.empty()) why = d.index_extended_ids();
  if (!why.empty()) {
    if (error) *error = why;
    return std::nullopt;
  }
  return d;
}

int Decoder::find_extended(std::uint32_t id) const {
  const std::size_t mask = extended_hash_.size() - 1;
  std::size_t slot = (id * 2654435769u) >> (32 - extended_hash_bits_);
  for (;;) {  // terminates: the table is at most half full
    const auto& e = extended_hash_[slot];
    if (e.second < 0) return -1;
    if (e.first == id) return e.second;
    slot = (slot + 1) & mask;
  }
}

SignalRef Decoder::find_signal(std::string_view message, std::string_view signal) const {
  const int m = db_.find_message(message);
  if (m < 0) return {};
  const int s = db_.messages[static_cast<std::size_t>(m)].find_signal(signal);
  if (s < 0) return {};
  return {m, s};
}

DecodeStatus Decoder::decode_into(const CanFrame& frame, int* message_index, double* values,
                                  std::uint8_t* present) const {
  int m = -1;
  const DecodeStatus st = classify(frame, &m);
  if (message_index) *message_index = m;
  if (st != DecodeStatus::kOk) return st;
  const CompiledMessage& cm = messages_[static_cast<std::size_t>(m)];
  std::memset(present, cm.switch_count == 0 ? 1 : 0, cm.signal_count);
  if (cm.switch_count == 0) return decode(frame, [&](int i, double v) { values[i] = v; });
  return decode(frame, [&](int i, double v) {
    values[i] = v;
    present[i] = 1;
  });
}

bool Decoder::signal_value(const CanFrame& frame, SignalRef ref, double* physical) const {
  if (!ref.valid() || ref.message >= message_count()) return false;
  const CompiledMessage& cm = messages_[static_cast<std::size_t>(ref.message)];
  if (frame.len < cm.length || static_cast<std::uint32_t>(ref.signal) >= cm.signal_count) {
    return false;
  }
  const CompiledSignal* sig = signals_.data() + cm.signal_begin;
  // Walk up the multiplexor chain: each link must select its child.
  const CompiledSignal* s = &sig[ref.signal];
  while (s->mux_parent >= 0) {
    const CompiledSignal& parent = sig[s->mux_parent];
    const auto raw = static_cast<std::uint64_t>(extract_raw(parent, frame.data)) & parent.mask;
    if (!in_ranges(*s, raw)) return false;
    s = &parent;
  }
  *physical = extract_physical(sig[ref.signal], frame.data);
  return true;
}

std::uint64_t Decoder::physical_to_raw(const CompiledSignal& s, double physical) const {
  const double scaled = (physical - s.offset) / s.factor;
  if (s.value_type == ValueType::kFloat32) {
    const auto f = static_cast<float>(scaled);
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
  }
  if (s.value_type == ValueType::kFloat64) {
    std::uint64_t u;
    std::memcpy(&u, &scaled, sizeof u);
    return u;
  }
  if (std::isnan(scaled)) return 0;
  const double r = std::round(scaled);
  if (s.is_signed) {
    const double lo = -std::ldexp(1.0, s.length - 1);
    const double hi = std::ldexp(1.0, s.length - 1);  // exclusive
    std::int64_t v;
    if (r <= lo) {
      v = s.length == 64 ? INT64_MIN : -(std::int64_t{1} << (s.length - 1));
    } else if (r >= hi) {
      v = s.length == 64 ? INT64_MAX : (std::int64_t{1} << (s.length - 1)) - 1;
    } else {
      v = static_cast<std::int64_t>(r);
    }
    return static_cast<std::uint64_t>(v) & s.mask;
  }
  if (r <= 0.0) return 0;
  if (r >= std::ldexp(1.0, s.length)) return s.mask;
  return static_cast<std::uint64_t>(r) & s.mask;
}

void Decoder::encode_signal(SignalRef ref, double physical, std::uint8_t* data) const {
  const CompiledSignal& s = compiled(ref);
  const std::uint64_t raw = physical_to_raw(s, physical);
  const Signal& sg = db_.messages[static_cast<std::size_t>(ref.message)]
                         .signals[static_cast<std::size_t>(ref.signal)];
  for (int i = 0; i < s.length; ++i) {
    int byte = 0, bit = 0;
    if (s.byte_order == ByteOrder::kIntel) {
      byte = (sg.start_bit + i) / 8;
      bit = (sg.start_bit + i) % 8;
    } else {
      const int lsb = (sg.start_bit / 8) * 8 + (7 - sg.start_bit % 8) + s.length - 1;
      const int p = lsb - i;  // big-endian linear position of raw bit i
      byte = p / 8;
      bit = 7 - p % 8;
    }
    const auto m = static_cast<std::uint8_t>(1u << bit);
    if ((raw >> i) & 1u) {
      data[byte] = static_cast<std::uint8_t>(data[byte] | m);
    } else {
      data[byte] = static_cast<std::uint8_t>(data[byte] & ~m);
    }
  }
}

bool Decoder::encode(int message_index, const double* values, CanFrame* frame) const {
  if (message_index < 0 || message_index >= message_count()) return false;
  const Message& m = db_.messages[static_cast<std::size_t>(message_index)];
  const CompiledMessage& cm = messages_[static_cast<std::size_t>(message_index)];
  frame->id = m.id;
  frame->flags = static_cast<std::uint8_t>((m.extended ? kExtended : 0) |
                                           (m.fd || m.length > kClassicMaxLen ? kFd : 0));
  frame->len = static_cast<std::uint8_t>(m.length);
  std::memset(frame->data, 0, sizeof frame->data);
  const CompiledSignal* sig = signals_.data() + cm.signal_begin;
  std::uint64_t switch_raw[kMaxSwitches] = {};
  std::uint32_t switch_present = 0;
  for (std::uint32_t k = 0; k < cm.signal_count; ++k) {
    const int i = order_[cm.order_begin + k];
    const CompiledSignal& s = sig[i];
    if (s.mux_parent >= 0) {
      const CompiledSignal& parent = sig[s.mux_parent];
      if ((switch_present & (1u << parent.switch_slot)) == 0 ||
          !in_ranges(s, switch_raw[parent.switch_slot])) {
        continue;
      }
    }
    encode_signal(SignalRef{message_index, i}, values[i], frame->data);
    if (s.switch_slot >= 0) {
      switch_raw[s.switch_slot] = physical_to_raw(s, values[i]);
      switch_present |= 1u << s.switch_slot;
    }
  }
  return true;
}

SignalSelection::SignalSelection(const Decoder& decoder)
    : decoder_(&decoder), by_message_(static_cast<std::size_t>(decoder.message_count())) {}

int SignalSelection::add(SignalRef ref) {
  if (!ref.valid() || ref.message >= decoder_->message_count() ||
      ref.signal >= static_cast<int>(decoder_->database()
                                         .messages[static_cast<std::size_t>(ref.message)]
                                         .signals.size())) {
    return -1;
  }
  const int slot = size();
  slots_.push_back(ref);
  by_message_[static_cast<std::size_t>(ref.message)].push_back({ref.signal, slot});
  return slot;
}

}  // namespace vmass::can
