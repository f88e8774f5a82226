#include "vmass/signals/signal_table.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::signals {

SignalTable::SignalTable(std::shared_ptr<const can::Decoder> decoder, const SignalMapping& mapping)
    : decoder_(std::move(decoder)), mapping_(mapping), selection_(*decoder_) {
  for (const InputMapping& m : mapping_.inputs) {
    Slot& slot = slots_[static_cast<std::size_t>(m.input)];
    slot.first_term = static_cast<int>(terms_.size());
    slot.offset = m.offset;
    for (const MappedSignal& s : m.terms) {
      Term t;
      if (s.mux_switch.valid()) {
        t.mux_switch = &decoder_->compiled(s.mux_switch);
        t.mux_value = s.mux_value;
      }
      t.scale = s.scale();
      t.has_range = s.has_range;
      t.minimum = s.minimum;
      t.maximum = s.maximum;
      t.tolerance = 1e-9 * std::max({1.0, std::abs(s.minimum), std::abs(s.maximum)});
      t.timeout_us = static_cast<TimeUs>(std::llround(s.timeout_s * 1e6));
      t.input = static_cast<int>(m.input);
      const int selection_slot = selection_.add(s.ref);
      if (selection_slot != static_cast<int>(terms_.size())) continue;  // invalid ref: unmapped
      terms_.push_back(t);
      ++slot.term_count;
    }
  }
}

can::DecodeStatus SignalTable::on_frame(const can::CanFrame& frame, TimeUs time_us) {
  ++counters_.frames;
  bool used = false;
  const can::DecodeStatus status = selection_.decode(frame, [&](int index, double physical) {
    Term& t = terms_[static_cast<std::size_t>(index)];
    if (t.mux_switch != nullptr) {
      const auto raw = static_cast<std::uint64_t>(decoder_->extract_raw(*t.mux_switch, frame.data));
      if ((raw & t.mux_switch->mask) != t.mux_value) return;  // another page
    }
    const double si = physical * t.scale;
    const bool good = std::isfinite(physical) && std::isfinite(si) &&
                      (!t.has_range || (physical >= t.minimum - t.tolerance &&
                                        physical <= t.maximum + t.tolerance));
    InputCounters& c = counters_.inputs[static_cast<std::size_t>(t.input)];
    ++c.updates;
    if (good) {
      t.value_si = si;
    } else {
      ++c.invalid_values;
    }
    t.good = good;
    t.time_us = time_us;
    used = true;
  });
  switch (status) {
    case can::DecodeStatus::kOk:
      ++counters_.decoded;
      if (used) ++counters_.mapped;
      break;
    case can::DecodeStatus::kUnknownId:
      ++counters_.unknown_id;
      break;
    case can::DecodeStatus::kTooShort:
      ++counters_.malformed;
      break;
    case can::DecodeStatus::kRemote:
      ++counters_.remote;
      break;
    case can::DecodeStatus::kErrorFrame:
      ++counters_.error_frames;
      break;
  }
  return status;
}

InputState SignalTable::input_state(Input input) const {
  InputState s;
  const Slot& slot = slots_[static_cast<std::size_t>(input)];
  if (slot.term_count == 0) return s;
  s.mapped = true;
  s.received = true;
  s.good = true;
  s.value = slot.offset;
  s.timeout_us = INT64_MAX;
  for (int k = 0; k < slot.term_count; ++k) {
    const Term& t = terms_[static_cast<std::size_t>(slot.first_term) + static_cast<std::size_t>(k)];
    s.timeout_us = std::min(s.timeout_us, t.timeout_us);
    if (t.time_us < 0) {
      s.received = false;
      s.good = false;
      continue;
    }
    if (!t.good) s.good = false;
    s.value += t.value_si;
    if (s.time_us < 0 || t.time_us < s.time_us) s.time_us = t.time_us;
  }
  if (!s.received) s.time_us = -1;
  return s;
}

TimeUs SignalTable::age_us(Input input, TimeUs now_us) const {
  const InputState s = input_state(input);
  if (!s.received) return -1;
  return std::max<TimeUs>(0, now_us - s.time_us);
}

Sample SignalTable::sample_at(TimeUs now_us) {
  Sample sample;
  sample.time_us = now_us;
  for (int i = 0; i < kInputCount; ++i) {
    Slot& slot = slots_[static_cast<std::size_t>(i)];
    if (slot.term_count == 0) continue;
    bool received = true;
    bool fresh = true;
    bool good = true;
    double value = slot.offset;
    for (int k = 0; k < slot.term_count; ++k) {
      const Term& t =
          terms_[static_cast<std::size_t>(slot.first_term) + static_cast<std::size_t>(k)];
      if (t.time_us < 0) {
        received = false;
        break;
      }
      if (now_us - t.time_us > t.timeout_us) fresh = false;
      if (!t.good) good = false;
      value += t.value_si;
    }
    fresh = fresh && received;
    if (slot.fresh && !fresh) ++counters_.inputs[static_cast<std::size_t>(i)].stale;
    slot.fresh = fresh;
    if (!fresh || !good || !std::isfinite(value)) continue;
    const auto input = static_cast<Input>(i);
    if (input == Input::kGear || input == Input::kBrakeSwitch) {
      if (!(std::abs(value) < 1000.0)) continue;
      value = std::nearbyint(value);
    }
    sample.set(input, value);
  }
  return sample;
}

void SignalTable::reset() {
  for (Term& t : terms_) {
    t.value_si = 0.0;
    t.time_us = -1;
    t.good = false;
  }
  for (Slot& s : slots_) s.fresh = false;
}

}  // namespace vmass::signals
