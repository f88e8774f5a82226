#include "vmass/scoring/truth.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>

namespace vmass::scoring {
namespace {

constexpr double kDriveStartSpeedMps = 0.5;

std::string seconds_text(TimeUs t) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f", to_seconds(t));
  return buf;
}

}  // namespace

Truth::Truth(std::vector<TimeUs> times, std::vector<double> masses_kg,
             std::vector<double> speeds_mps)
    : times_(std::move(times)),
      masses_kg_(std::move(masses_kg)),
      speeds_mps_(std::move(speeds_mps)) {}

double Truth::mass_at(TimeUs t) const {
  if (times_.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto it = std::upper_bound(times_.begin(), times_.end(), t);
  if (it == times_.begin()) return masses_kg_.front();
  return masses_kg_[static_cast<std::size_t>(it - times_.begin()) - 1];
}

TimeUs Truth::drive_start_us() const {
  for (std::size_t i = 0; i < speeds_mps_.size(); ++i) {
    if (speeds_mps_[i] > kDriveStartSpeedMps) return times_[i];
  }
  return times_.empty() ? 0 : times_.front();
}

std::string Truth::check_time_base(TimeUs first_tick_us, TimeUs tick_period_us) const {
  if (first_tick_us >= first_time_us() - tick_period_us &&
      first_tick_us <= last_time_us() + tick_period_us) {
    return "";
  }
  return "its times (" + seconds_text(first_time_us()) + " to " + seconds_text(last_time_us()) +
         " s) do not contain the input's first tick (" + seconds_text(first_tick_us) +
         " s): another time base (a log with epoch times needs a truth in the same times)";
}

}  // namespace vmass::scoring
