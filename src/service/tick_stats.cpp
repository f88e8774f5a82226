#include "vmass/service/tick_stats.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::service {

int LogHistogram::bin_of(std::int64_t value) {
  if (value < 0) value = 0;
  if (value < kLinearBins) return static_cast<int>(value);
  const int exponent = 63 - __builtin_clzll(static_cast<unsigned long long>(value));  // >= 7
  if (exponent >= kMaxExponent) return kBins - 1;
  const int sub = static_cast<int>((value >> (exponent - 6)) & (kSubBins - 1));
  return kLinearBins + (exponent - 7) * kSubBins + sub;
}

std::int64_t LogHistogram::bin_upper(int bin) {
  if (bin < kLinearBins) return bin;
  const int exponent = 7 + (bin - kLinearBins) / kSubBins;
  const std::int64_t sub = (bin - kLinearBins) % kSubBins;
  const std::int64_t width = std::int64_t{1} << (exponent - 6);
  return (std::int64_t{1} << exponent) + (sub + 1) * width - 1;
}

void LogHistogram::add(std::int64_t value) {
  if (value < 0) value = 0;
  ++bins_[static_cast<std::size_t>(bin_of(value))];
  ++count_;
  max_ = std::max(max_, value);
}

void LogHistogram::clear() {
  bins_.fill(0);
  count_ = 0;
  max_ = 0;
}

std::int64_t LogHistogram::percentile(double q) const {
  if (count_ == 0) return 0;
  q = std::clamp(q, 0.0, 1.0);
  const auto needed = std::max<std::int64_t>(
      1, static_cast<std::int64_t>(std::ceil(q * static_cast<double>(count_))));
  std::int64_t seen = 0;
  for (int b = 0; b < kBins; ++b) {
    seen += bins_[static_cast<std::size_t>(b)];
    if (seen >= needed) return std::min(bin_upper(b), max_);
  }
  return max_;
}

void TickStats::on_wake(std::int64_t deadline_ns, std::int64_t wake_ns) {
  ++ticks_;
  wake_latency_max_ns_ = std::max(wake_latency_max_ns_, wake_ns - deadline_ns);
  if (has_last_wake_) {
    const std::int64_t jitter_ns = std::abs((wake_ns - last_wake_ns_) - period_ns_);
    jitter_us_.add((jitter_ns + 500) / 1000);
  }
  last_wake_ns_ = wake_ns;
  has_last_wake_ = true;
}

void TickStats::on_done(std::int64_t compute_ns, bool overrun) {
  compute_max_ns_ = std::max(compute_max_ns_, compute_ns);
  if (overrun) ++overruns_;
}

TickTimingSummary TickStats::summary() const {
  TickTimingSummary s;
  s.ticks = ticks_;
  s.overruns = overruns_;
  s.skipped = skipped_;
  s.jitter_p50_us = static_cast<double>(jitter_us_.percentile(0.50));
  s.jitter_p99_us = static_cast<double>(jitter_us_.percentile(0.99));
  s.jitter_max_us = static_cast<double>(jitter_us_.max());
  s.wake_latency_max_us = static_cast<double>(wake_latency_max_ns_) * 1e-3;
  s.compute_max_us = static_cast<double>(compute_max_ns_) * 1e-3;
  return s;
}

}  // namespace vmass::service
