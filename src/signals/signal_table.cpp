#include "vmass/signals/signal_table.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::signals {
namespace {

constexpr double kBurstFrames = 3.0;  ///< too-fast bucket: frames of burst allowed
constexpr double kRateFactor = 2.0;   ///< refilled at twice the nominal rate

}  // namespace

SignalTable::SignalTable(std::shared_ptr<const can::Decoder> decoder, const SignalMapping& mapping)
    : decoder_(std::move(decoder)),
      mapping_(mapping),
      selection_(*decoder_),
      watched_slot_(static_cast<std::size_t>(decoder_->message_count()), -1) {
  // Watched messages in DBC order: the mapped ones and the protected ones.
  std::vector<bool> watch(static_cast<std::size_t>(decoder_->message_count()), false);
  for (const InputMapping& m : mapping_.inputs) {
    for (const MappedSignal& s : m.terms) {
      if (s.ref.valid()) watch[static_cast<std::size_t>(s.ref.message)] = true;
    }
  }
  for (const ProtectedMessage& p : mapping_.protection.messages) {
    watch[static_cast<std::size_t>(p.message)] = true;
  }
  for (int i = 0; i < decoder_->message_count(); ++i) {
    if (watch[static_cast<std::size_t>(i)] && watched_count() < kMaxWatchedMessages) {
      add_watched(i, mapping_);
    }
  }
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
      t.has_range = s.has_range && mapping_.enforce_dbc_ranges;
      t.minimum = s.minimum;
      t.maximum = s.maximum;
      t.tolerance = 1e-9 * std::max({1.0, std::abs(s.minimum), std::abs(s.maximum)});
      t.timeout_us = static_cast<TimeUs>(std::llround(s.timeout_s * 1e6));
      t.input = static_cast<int>(m.input);
      const int selection_slot = selection_.add(s.ref);
      if (selection_slot != static_cast<int>(terms_.size())) continue;  // invalid ref: unmapped
      t.message_slot = watched_slot_[static_cast<std::size_t>(s.ref.message)];
      Watched& w = messages_[static_cast<std::size_t>(t.message_slot)];
      w.feeds |= input_bit(m.input);
      // A gap longer than the shortest timeout of the message's terms restarts its counter.
      w.resync_after_us = std::min(w.resync_after_us, t.timeout_us);
      terms_.push_back(t);
      ++slot.term_count;
    }
  }
  staged_.reserve(terms_.size());  // a frame stages at most every term
}

void SignalTable::add_watched(int message, const SignalMapping& mapping) {
  const can::Message& m = decoder_->database().messages[static_cast<std::size_t>(message)];
  Watched w;
  w.index = message;
  w.e2e = mapping.protection.find(message);
  w.validity =
      can::MessageValidity(mapping.protection.invalid_after, mapping.protection.valid_after);
  w.length = static_cast<std::uint8_t>(m.length);
  if (m.cycle_time_ms > 0) w.tokens_per_us = kRateFactor / (m.cycle_time_ms * 1000.0);
  // Like the default input timeout: 5 cycles, 0.1 s without a cycle time; shortened below to
  // the timeouts of the terms the message feeds.
  w.resync_after_us =
      m.cycle_time_ms > 0 ? 5 * 1000 * static_cast<TimeUs>(m.cycle_time_ms) : 100'000;
  watched_slot_[static_cast<std::size_t>(message)] = static_cast<int>(messages_.size());
  messages_.push_back(w);
}

can::DecodeStatus SignalTable::on_frame(const can::CanFrame& frame, TimeUs time_us) {
  ++counters_.frames;
  int m = -1;
  const can::DecodeStatus status = decoder_->classify(frame, &m);
  bool used = false;
  if (status == can::DecodeStatus::kOk) {
    const int slot = watched_slot_[static_cast<std::size_t>(m)];
    if (slot >= 0 && admit(messages_[static_cast<std::size_t>(slot)], frame, time_us)) {
      used = commit(m, frame, time_us);
    }
  }
  count_status(status, used);
  return status;
}

bool SignalTable::admit(Watched& w, const can::CanFrame& frame, TimeUs time_us) {
  ++w.counters.frames;
  const bool resync = w.last_time_us == kNeverUs || time_us - w.last_time_us > w.resync_after_us;
  const bool too_fast = count_timing(w, frame, time_us);
  can::E2eResult result = can::E2eResult::kOk;
  if (w.e2e != nullptr) result = can::check_e2e(*decoder_, *w.e2e, frame, resync, &w.e2e_state);
  if (result != can::E2eResult::kOk) count_e2e_failure(w, result);
  // A protected message's frame that comes far too soon is not believed either: a spoofer
  // replaying its own counter sequence at ten times the rate passes the counter check.
  const bool passed = result == can::E2eResult::kOk && !(too_fast && w.e2e != nullptr);
  const bool commit = w.validity.on_frame(passed);
  if (passed && !commit) ++w.counters.withheld;
  if (commit) ++w.counters.committed;
  return commit;
}

bool SignalTable::count_timing(Watched& w, const can::CanFrame& frame, TimeUs time_us) {
  if (frame.len > w.length) ++w.counters.too_long;
  bool too_fast = false;
  if (w.tokens_per_us > 0.0) {
    if (w.last_time_us == kNeverUs) {
      w.tokens = kBurstFrames;
    } else {
      const double elapsed = static_cast<double>(std::max<TimeUs>(0, time_us - w.last_time_us));
      w.tokens = std::min(kBurstFrames, w.tokens + elapsed * w.tokens_per_us);
    }
    too_fast = w.tokens < 1.0;
    if (too_fast) {
      ++w.counters.too_fast;
    } else {
      w.tokens -= 1.0;
    }
  }
  w.last_time_us = time_us;
  return too_fast;
}

void SignalTable::count_e2e_failure(Watched& w, can::E2eResult result) {
  const bool counter = result == can::E2eResult::kCounterFail;
  ++(counter ? w.counters.counter_fail : w.counters.checksum_fail);
  for (int i = 0; i < kInputCount; ++i) {
    if ((w.feeds & input_bit(static_cast<Input>(i))) == 0) continue;
    InputCounters& c = counters_.inputs[static_cast<std::size_t>(i)];
    ++(counter ? c.counter_fail : c.checksum_fail);
  }
}

bool SignalTable::commit(int m, const can::CanFrame& frame, TimeUs time_us) {
  staged_.clear();  // within its reserved capacity: no allocation
  selection_.decode_message(m, frame, [&](int index, double physical) {
    const Term& t = terms_[static_cast<std::size_t>(index)];
    if (t.mux_switch != nullptr) {
      const auto raw = static_cast<std::uint64_t>(decoder_->extract_raw(*t.mux_switch, frame.data));
      if ((raw & t.mux_switch->mask) != t.mux_value) return;  // another page
    }
    staged_.push_back(Staged{index, physical});
  });
  for (const Staged& s : staged_) {
    Term& t = terms_[static_cast<std::size_t>(s.term)];
    const double si = s.physical * t.scale;
    const bool good = std::isfinite(s.physical) && std::isfinite(si) &&
                      (!t.has_range || (s.physical >= t.minimum - t.tolerance &&
                                        s.physical <= t.maximum + t.tolerance));
    InputCounters& c = counters_.inputs[static_cast<std::size_t>(t.input)];
    ++c.updates;
    if (good) {
      t.value_si = si;
    } else {
      ++c.invalid_values;
    }
    t.good = good;
    t.time_us = time_us;
  }
  return !staged_.empty();
}

void SignalTable::count_status(can::DecodeStatus status, bool used) {
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
    if (t.time_us == kNeverUs) {
      s.received = false;
      s.good = false;
      continue;
    }
    if (!t.good) s.good = false;
    s.value += t.value_si;
    if (s.time_us == kNeverUs || t.time_us < s.time_us) s.time_us = t.time_us;
  }
  if (!s.received) s.time_us = kNeverUs;
  return s;
}

TimeUs SignalTable::age_us(Input input, TimeUs now_us) const {
  const InputState s = input_state(input);
  if (!s.received) return -1;
  return std::max<TimeUs>(0, now_us - s.time_us);
}

bool SignalTable::bus_valid() const {
  for (const Watched& w : messages_) {
    if (!w.validity.valid()) return false;
  }
  return true;
}

InputFault SignalTable::evaluate(int i, TimeUs now_us, double* value) {
  Slot& slot = slots_[static_cast<std::size_t>(i)];
  InputVerdict& v = verdicts_[static_cast<std::size_t>(i)];
  bool fresh = true, good = true;
  *value = slot.offset;
  v = InputVerdict{};
  for (int k = 0; k < slot.term_count; ++k) {
    const Term& t = terms_[static_cast<std::size_t>(slot.first_term) + static_cast<std::size_t>(k)];
    if (t.time_us == kNeverUs) {
      v.fault = InputFault::kNotReceived;
      slot.fresh = false;
      return v.fault;
    }
    const Watched& w = messages_[static_cast<std::size_t>(t.message_slot)];
    if (!w.validity.valid() && v.fault == InputFault::kNone) {
      v.fault = InputFault::kMessageInvalid;
      v.message = w.index;
    }
    if (now_us - t.time_us > t.timeout_us && fresh) {
      fresh = false;
      v.value = static_cast<double>(now_us - t.time_us) * 1e-6;
      v.bound = static_cast<double>(t.timeout_us) * 1e-6;
    }
    good = good && t.good;
    *value += t.value_si;
  }
  if (slot.fresh && !fresh) ++counters_.inputs[static_cast<std::size_t>(i)].stale;
  slot.fresh = fresh;
  if (v.fault != InputFault::kNone) return v.fault;
  if (!fresh) v.fault = InputFault::kStale;
  if (fresh && (!good || !std::isfinite(*value))) v.fault = InputFault::kInvalidValue;
  return v.fault;
}

Sample SignalTable::sample_at(TimeUs now_us) {
  Sample sample;
  sample.time_us = now_us;
  for (int i = 0; i < kInputCount; ++i) {
    if (slots_[static_cast<std::size_t>(i)].term_count == 0) continue;
    double value = 0.0;
    if (evaluate(i, now_us, &value) != InputFault::kNone) continue;
    const auto input = static_cast<Input>(i);
    if (input == Input::kGear || input == Input::kBrakeSwitch) {
      if (!(std::abs(value) < 1000.0)) {
        verdicts_[static_cast<std::size_t>(i)].fault = InputFault::kInvalidValue;
        continue;
      }
      value = std::nearbyint(value);
    }
    sample.set(input, value);
  }
  return sample;
}

void SignalTable::reset() {
  for (Term& t : terms_) {
    t.value_si = 0.0;
    t.time_us = kNeverUs;
    t.good = false;
  }
  for (Slot& s : slots_) s.fresh = false;
  for (Watched& w : messages_) {
    w.e2e_state = can::E2eState{};
    w.validity =
        can::MessageValidity(mapping_.protection.invalid_after, mapping_.protection.valid_after);
    w.last_time_us = kNeverUs;
  }
  verdicts_.fill(InputVerdict{});
}

}  // namespace vmass::signals
