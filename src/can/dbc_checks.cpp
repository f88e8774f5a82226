// The pass after the DBC text: multiplexing attached, every signal checked against its message
// (layout, overlaps), attribute defaults applied. See dbc_parser.hpp.
#include <algorithm>
#include <bitset>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

#include "dbc_parser.hpp"

namespace vmass::can::dbc_detail {

void Parser::finish() {
  // Attribute defaults.
  const AttributeDefinition* cycle = attribute("GenMsgCycleTime");
  const AttributeDefinition* format = attribute("VFrameFormat");
  for (std::size_t i = 0; i < db_.messages.size(); ++i) {
    Message& m = db_.messages[i];
    if (cycle && !cycle->default_value.empty() &&
        explicit_cycle_.count(static_cast<long>(i)) == 0) {
      double v = 0.0;
      const char* b = cycle->default_value.data();
      if (std::from_chars(b, b + cycle->default_value.size(), v).ec == std::errc() && v >= 0 &&
          v < 1e9) {
        m.cycle_time_ms = static_cast<int>(v);
      }
    }
    if (format && !format->default_value.empty() &&
        explicit_format_.count(static_cast<long>(i)) == 0) {
      m.fd = frame_format_is_fd(format->default_value);
    }
    if (m.length > kClassicMaxLen) m.fd = true;  // only CAN FD carries more than 8 bytes
  }
  // Signals the tables cannot hold are reported and left out, so that the rest of the file
  // stays usable; the result is not ok().
  for (Message& m : db_.messages) check_layout(m);
  for (std::size_t i = 0; i < db_.messages.size(); ++i) index_signals(i);  // after the drops
  // Extended multiplexing (by name, so after the layout pass removed signals).
  for (const MulValEntry& e : mul_vals_) {
    const int msg = message_for(e.raw_id, "SG_MUL_VAL_");
    Signal* sg = signal_for(msg, e.signal, "SG_MUL_VAL_");
    if (sg == nullptr) continue;
    Message& m = db_.messages[static_cast<std::size_t>(msg)];
    const auto& index = signal_index_[static_cast<std::size_t>(msg)];
    const auto found = index.find(e.switch_name);
    const int sw = found == index.end() ? -1 : found->second;
    if (sw < 0 || !m.signals[static_cast<std::size_t>(sw)].is_multiplexor) {
      error_at(e.line, "SG_MUL_VAL_ " + e.signal + ": " + e.switch_name +
                           " is not a multiplexor of message " + m.name);
      sg->mux_parent = kMuxBroken;
      continue;
    }
    sg->mux_parent = sw;
    sg->mux_ranges = e.ranges;
  }
  for (Message& m : db_.messages) resolve_mux(m);
}

void Parser::check_layout(Message& m) {
  const int payload_bits = 8 * m.length;
  std::unordered_set<std::string_view> names;
  std::vector<bool> drop(m.signals.size(), false);
  for (std::size_t i = 0; i < m.signals.size(); ++i) {
    const Signal& sg = m.signals[i];
    const std::string who = "signal " + sg.name + " of message " + m.name;
    if (!names.insert(sg.name).second) {
      error_at(sg.line, who + ": name used twice; the second is left out");
      drop[i] = true;
      continue;
    }
    if (sg.length < 1 || sg.length > 64) {
      error_at(sg.line, who + ": length " + std::to_string(sg.length) + " is not 1..64 bits");
      drop[i] = true;
      continue;
    }
    if ((sg.value_type == ValueType::kFloat32 && sg.length != 32) ||
        (sg.value_type == ValueType::kFloat64 && sg.length != 64)) {
      error_at(sg.line, who + ": SIG_VALTYPE_ float needs a length of " +
                            (sg.value_type == ValueType::kFloat32 ? "32" : "64") + " bits");
      drop[i] = true;
      continue;
    }
    int last = 0;  // last bit in the layout's own linear numbering
    if (sg.byte_order == ByteOrder::kIntel) {
      last = sg.start_bit + sg.length - 1;
    } else {
      last = (sg.start_bit / 8) * 8 + (7 - sg.start_bit % 8) + sg.length - 1;
    }
    check_declared_range(m, sg);
    if (last >= payload_bits) {
      error_at(sg.line,
               who + ": bits " + std::to_string(sg.start_bit) + "|" + std::to_string(sg.length) +
                   "@" + (sg.byte_order == ByteOrder::kIntel ? "1" : "0") + " do not fit in the " +
                   std::to_string(m.length) + "-byte payload; signal left out");
      drop[i] = true;
    }
  }
  std::vector<Signal> kept;
  kept.reserve(m.signals.size());
  for (std::size_t i = 0; i < m.signals.size(); ++i) {
    if (!drop[i]) kept.push_back(std::move(m.signals[i]));
  }
  m.signals = std::move(kept);
}

void Parser::resolve_mux(Message& m) {
  int roots = 0, root = -1;
  for (std::size_t i = 0; i < m.signals.size(); ++i) {
    const Signal& sg = m.signals[i];
    if (sg.is_multiplexor && !sg.mux_value) {
      ++roots;
      root = static_cast<int>(i);
    }
  }
  std::vector<bool> drop(m.signals.size(), false);
  for (std::size_t i = 0; i < m.signals.size(); ++i) {
    Signal& sg = m.signals[i];
    if (sg.mux_parent == kMuxBroken) {
      drop[i] = true;
      continue;
    }
    if (sg.mux_value && sg.mux_parent < 0) {
      if (roots == 1 && root != static_cast<int>(i)) {
        sg.mux_parent = root;
        sg.mux_ranges = {MuxRange{*sg.mux_value, *sg.mux_value}};
      } else {
        error_at(sg.line, "signal " + sg.name + " of message " + m.name + " is multiplexed (m" +
                              std::to_string(*sg.mux_value) + ") but " +
                              (roots == 0 ? "the message has no multiplexor (M)"
                                          : "the message has several multiplexors and no "
                                            "SG_MUL_VAL_ names this signal's") +
                              "; signal left out");
        drop[i] = true;
      }
    }
  }
  // A chain that loops, or that runs through a dropped switch, drops the signal.
  bool changed = true;
  while (changed) {
    changed = false;
    for (std::size_t i = 0; i < m.signals.size(); ++i) {
      if (drop[i]) continue;
      int p = m.signals[i].mux_parent;
      std::size_t steps = 0;
      bool bad = false;
      while (p >= 0) {
        if (drop[static_cast<std::size_t>(p)] || ++steps > m.signals.size()) {
          bad = true;
          break;
        }
        p = m.signals[static_cast<std::size_t>(p)].mux_parent;
      }
      if (bad) {
        error_at(m.signals[i].line, "signal " + m.signals[i].name + " of message " + m.name +
                                        ": its multiplexor chain is broken or loops; "
                                        "signal left out");
        drop[i] = true;
        changed = true;
      }
    }
  }
  std::vector<int> new_index(m.signals.size(), -1);
  std::vector<Signal> kept;
  for (std::size_t i = 0; i < m.signals.size(); ++i) {
    if (drop[i]) continue;
    new_index[i] = static_cast<int>(kept.size());
    kept.push_back(std::move(m.signals[i]));
  }
  for (Signal& sg : kept) {
    if (sg.mux_parent >= 0) sg.mux_parent = new_index[static_cast<std::size_t>(sg.mux_parent)];
  }
  m.signals = std::move(kept);
  check_overlaps(m);
  check_mux_values(m);
}

void Parser::check_declared_range(const Message& m, const Signal& sg) {
  if (!sg.has_range || sg.value_type != ValueType::kInteger || sg.factor == 0.0) return;
  // What the bits carry, in physical units (half a step of tolerance for rounded ranges).
  const double raw_lo = sg.is_signed ? -std::ldexp(1.0, sg.length - 1) : 0.0;
  const double raw_hi =
      sg.is_signed ? std::ldexp(1.0, sg.length - 1) - 1.0 : std::ldexp(1.0, sg.length) - 1.0;
  const double a = raw_lo * sg.factor + sg.offset, b = raw_hi * sg.factor + sg.offset;
  // Slack: half a step, and ranges rounded to 5 significant digits (429497000 for 2^32 * 0.1).
  const double lo = std::min(a, b), hi = std::max(a, b);
  const double slack = std::max(std::abs(sg.factor) / 2.0, 1e-5 * (hi - lo));
  if (sg.minimum >= lo - slack && sg.maximum <= hi + slack) return;
  char text[160];
  std::snprintf(text, sizeof text,
                "declared range [%.10g|%.10g] lies outside what its %d %s bits carry [%.10g|%.10g]",
                sg.minimum, sg.maximum, sg.length, sg.is_signed ? "signed" : "unsigned", lo, hi);
  warning(sg.line, "signal " + sg.name + " of message " + m.name + ": " + text +
                       "; vmass does not discard values by DBC ranges");
}

void Parser::check_mux_values(const Message& m) {
  for (const Signal& sg : m.signals) {
    if (sg.mux_parent < 0 || sg.mux_ranges.empty()) continue;
    const Signal& sw = m.signals[static_cast<std::size_t>(sg.mux_parent)];
    const std::uint64_t max_raw = sw.length >= 64 ? ~0ull : (1ull << sw.length) - 1;
    bool reachable = false;
    for (const MuxRange& r : sg.mux_ranges) reachable = reachable || r.lo <= max_raw;
    if (!reachable) {
      warning(sg.line, "signal " + sg.name + " of message " + m.name +
                           " can never be present: its multiplexer value " +
                           std::to_string(sg.mux_ranges.front().lo) + " exceeds what switch " +
                           sw.name + " (" + std::to_string(sw.length) + " bits) can hold");
    }
  }
}

std::bitset<8 * kFdMaxLen> Parser::bits_of(const Signal& sg) {
  std::bitset<8 * kFdMaxLen> b;
  int p = sg.byte_order == ByteOrder::kIntel ? sg.start_bit
                                             : (sg.start_bit / 8) * 8 + (7 - sg.start_bit % 8);
  for (int i = 0; i < sg.length; ++i, ++p) {
    // Both layouts as positions in their own linear order; map Motorola back to bit numbers.
    const int bit = sg.byte_order == ByteOrder::kIntel ? p : (p / 8) * 8 + (7 - p % 8);
    if (bit >= 0 && bit < 8 * kFdMaxLen) b.set(static_cast<std::size_t>(bit));
  }
  return b;
}

Parser::MuxChain Parser::mux_chain(const Message& m, std::size_t i) {
  MuxChain chain;
  const Signal* s = &m.signals[i];
  while (s->mux_parent >= 0 && chain.size() <= m.signals.size()) {
    chain.emplace_back(s->mux_parent, &s->mux_ranges);
    s = &m.signals[static_cast<std::size_t>(s->mux_parent)];
  }
  return chain;
}

bool Parser::can_coexist(const MuxChain& a, const MuxChain& b, long* work) {
  for (const auto& [p, ra] : a) {
    for (const auto& [q, rb] : b) {
      if (p != q) continue;
      *work += static_cast<long>(ra->size() * rb->size());
      bool meet = false;
      for (const MuxRange& x : *ra) {
        for (const MuxRange& y : *rb) meet = meet || (x.lo <= y.hi && y.lo <= x.hi);
      }
      if (!meet) return false;
    }
  }
  return true;
}

void Parser::check_overlaps(const Message& m) {
  std::vector<std::bitset<8 * kFdMaxLen>> bits;
  std::vector<MuxChain> chains;
  bits.reserve(m.signals.size());
  chains.reserve(m.signals.size());
  for (std::size_t i = 0; i < m.signals.size(); ++i) {
    bits.push_back(bits_of(m.signals[i]));
    chains.push_back(mux_chain(m, i));
  }
  // Pairwise, with a bound on the work: a file may give a message thousands of multiplexed
  // signals over the same bits, each selected by many ranges.
  constexpr long kMaxWork = 20'000'000;
  long work = 0;
  for (std::size_t i = 0; i < m.signals.size(); ++i) {
    if (work > kMaxWork) {
      warning(m.signals[i].line, "message " + m.name + ": overlaps not checked from signal " +
                                     m.signals[i].name + " on (too many signals share bits)");
      return;
    }
    for (std::size_t j = 0; j < i; ++j) {
      ++work;
      if ((bits[i] & bits[j]).any() && can_coexist(chains[i], chains[j], &work)) {
        deviation(m.signals[i].line, "signal " + m.signals[i].name + " of message " + m.name +
                                         " overlaps signal " + m.signals[j].name);
        break;
      }
    }
  }
}

std::string Parser::hex(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%X", v);
  return buf;
}

}  // namespace vmass::can::dbc_detail
