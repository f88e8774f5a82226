#include "vmass/core/speed_refresh.hpp"

#include <cmath>
#include <limits>

namespace vmass {

SpeedRefresh::SpeedRefresh(const SpeedRefreshParams& params) : params_(params) {}

void SpeedRefresh::observe(TimeUs time_us, double speed_mps) {
  if (!std::isfinite(speed_mps)) {
    in_block_ = false;
    return;
  }
  const bool gap =
      in_block_ && (time_us <= last_us_ || to_seconds(time_us - last_us_) > params_.max_tick_gap_s);
  if (!in_block_ || gap) {
    start_block(time_us, speed_mps);
    return;
  }
  if (speed_mps != last_speed_mps_) ++block_changes_;
  if (std::abs(speed_mps) < params_.min_speed_mps) block_above_min_speed_ = false;
  last_us_ = time_us;
  last_speed_mps_ = speed_mps;
  if (to_seconds(time_us - block_start_us_) >= params_.block_s) close_block(time_us, speed_mps);
}

void SpeedRefresh::start_block(TimeUs time_us, double speed_mps) {
  in_block_ = true;
  block_above_min_speed_ = std::abs(speed_mps) >= params_.min_speed_mps;
  block_start_us_ = time_us;
  block_start_speed_mps_ = speed_mps;
  block_changes_ = 0;
  last_us_ = time_us;
  last_speed_mps_ = speed_mps;
}

void SpeedRefresh::close_block(TimeUs time_us, double speed_mps) {
  const double duration_s = to_seconds(time_us - block_start_us_);
  const double change_mps = std::abs(speed_mps - block_start_speed_mps_);
  if (block_above_min_speed_ && change_mps >= params_.min_change_mps_per_s * duration_s) {
    counted_s_ += duration_s;
    counted_changes_ += block_changes_;
    ++counted_blocks_;
  }
  start_block(time_us, speed_mps);
}

bool SpeedRefresh::coarse() const {
  return decided() && mean_interval_s() > params_.max_mean_interval_s;
}

double SpeedRefresh::mean_interval_s() const {
  return counted_changes_ > 0 ? counted_s_ / static_cast<double>(counted_changes_)
                              : std::numeric_limits<double>::infinity();
}

}  // namespace vmass
