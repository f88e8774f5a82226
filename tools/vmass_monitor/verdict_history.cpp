#include "verdict_history.hpp"

#include <algorithm>
#include <cstddef>
#include <iterator>

namespace vmass::monitor {

void VerdictHistory::add(double t_s, const vmass::status_t& status) {
  const auto n = static_cast<std::size_t>(std::max(status.num_verdicts, 0));
  if (n == 0 || status.verdict_name.size() != n || status.longitudinal_verdict_ticks.size() != n) {
    return;
  }
  Snapshot s{t_s, status.ticks, status.tick_rate_hz, status.longitudinal_verdict_ticks};
  bool restarted = status.verdict_name != names_;
  if (!restarted && !snapshots_.empty()) {
    const Snapshot& last = snapshots_.back();
    restarted = s.ticks < last.ticks;
    for (std::size_t i = 0; i < n && !restarted; ++i) restarted = s.counts[i] < last.counts[i];
  }
  if (restarted) {
    snapshots_.clear();
    names_ = status.verdict_name;
  }
  snapshots_.push_back(std::move(s));
  while (snapshots_.size() > 2 && snapshots_.front().t_s < t_s - keep_s_) snapshots_.pop_front();
}

NoPairStretch VerdictHistory::no_pair() const {
  NoPairStretch out;
  if (snapshots_.size() < 2) return out;
  const Snapshot& newest = snapshots_.back();
  // The oldest snapshot of the run of those with the newest's accepted count (index 0).
  auto oldest = snapshots_.rbegin();
  while (std::next(oldest) != snapshots_.rend() && std::next(oldest)->counts[0] == newest.counts[0])
    ++oldest;
  const std::int64_t ticks = newest.ticks - oldest->ticks;
  if (ticks <= 0 || !(newest.tick_rate_hz > 0.0)) return out;
  const double span_s = static_cast<double>(ticks) / newest.tick_rate_hz;
  if (span_s < shortest_s_) return out;
  out.span_s = span_s;
  for (std::size_t i = 1; i < names_.size(); ++i) {
    const std::int64_t d = newest.counts[i] - oldest->counts[i];
    if (d > 0) out.verdict_ticks.emplace_back(names_[i], d);
  }
  std::stable_sort(out.verdict_ticks.begin(), out.verdict_ticks.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  return out;
}

}  // namespace vmass::monitor
