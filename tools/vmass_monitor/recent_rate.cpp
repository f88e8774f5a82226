#include "recent_rate.hpp"

#include <algorithm>

namespace vmass::monitor {

namespace {
constexpr double kSilentPeriods = 3.0;
constexpr double kShortestSilenceS = 3.0;
constexpr double kShortestWindowS = 5.0;
}  // namespace

double silence_limit_s(double status_period_s, double mean_estimate_interval_s) {
  return std::max({kShortestSilenceS, kSilentPeriods * status_period_s,
                   kSilentPeriods * mean_estimate_interval_s});
}

double rate_window_s(double status_period_s) {
  return std::max(kShortestWindowS, kSilentPeriods * status_period_s);
}

void RecentRate::add(double t_s) {
  if (count_ == 0) first_ = t_s;
  last_ = t_s;
  ++count_;
  times_.push_back(t_s);
  while (times_.front() <= t_s - window_s_) times_.pop_front();
}

double RecentRate::rate_hz(double now_s) {
  while (!times_.empty() && times_.front() <= now_s - window_s_) times_.pop_front();
  if (times_.size() < 2) return 0.0;
  const auto n = static_cast<double>(times_.size());
  const double since_first = now_s - times_.front();
  const double spread = times_.back() - times_.front();
  const double bound = since_first > 0.0 ? n / since_first : 0.0;
  return spread > 0.0 ? std::min((n - 1.0) / spread, bound) : bound;
}

double RecentRate::mean_interval_s() const {
  return count_ > 1 ? (last_ - first_) / static_cast<double>(count_ - 1) : 0.0;
}

}  // namespace vmass::monitor
