#include "vmass/runtime/samples_csv_source.hpp"

namespace vmass::runtime {

SamplesCsvSource::SamplesCsvSource(const std::string& path, double timeout_s)
    : path_(path), reader_(path) {
  for (TimeUs& t : timeouts_.timeout_us) t = from_seconds(timeout_s);
}

std::unique_ptr<SamplesCsvSource> SamplesCsvSource::open(const std::string& path, double timeout_s,
                                                         std::string* error) {
  std::unique_ptr<SamplesCsvSource> source(new SamplesCsvSource(path, timeout_s));
  if (!source->reader_.error().empty()) {
    if (error) *error = source->reader_.error();
    return nullptr;
  }
  return source;
}

InputSource::Read SamplesCsvSource::next_record(int /*timeout_ms*/) {
  for (;;) {
    if (guard_.pop(&record_, ended_)) {
      publish_clock_counters(guard_.counters());
      return Read::kRecord;
    }
    if (ended_) {
      publish_clock_counters(guard_.counters());
      set_health(SourceState::kEnded,
                 reader_.read_error().empty() ? "end of " + path_ : reader_.read_error());
      return Read::kEnd;
    }
    const long skipped_before = reader_.skipped_rows();
    std::optional<Sample> row = reader_.next();
    const long skipped = reader_.skipped_rows() - skipped_before;
    if (skipped > 0) {
      counters_.received.fetch_add(skipped, std::memory_order_relaxed);
      counters_.malformed.fetch_add(skipped, std::memory_order_relaxed);
    }
    if (!row) {
      ended_ = true;
      continue;
    }
    counters_.received.fetch_add(1, std::memory_order_relaxed);
    guard_.push(*row);
  }
}

void SamplesCsvSource::copy_record(InputRecord* record) const {
  record->time_us = record_.time_us;
  record->sample = record_;
}

void SamplesCsvSource::apply(const InputRecord& record) {
  values_.latest = record.sample;
  values_.latest.time_us = record.time_us;
  for (TimeUs& t : values_.input_time_us) t = record.time_us;
  values_.last_update_us = record.time_us;
  ++values_.updates;
  counters_.decoded.fetch_add(1, std::memory_order_relaxed);
}

Sample SamplesCsvSource::sample_at(TimeUs tick_us) {
  return runtime::sample_at(values_, tick_us, timeouts_);
}

TimeUs SamplesCsvSource::input_age_us(Input input, TimeUs tick_us) const {
  const TimeUs t = values_.input_time_us[static_cast<int>(input)];
  return t == signals::kNeverUs ? -1 : tick_us - t;
}

}  // namespace vmass::runtime
