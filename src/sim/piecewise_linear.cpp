#include "vmass/sim/piecewise_linear.hpp"

#include <algorithm>
#include <cmath>

namespace vmass::sim {

namespace {

// Index i of the segment [x_i, x_{i+1}) containing x, for 1 <= points.size(); x inside the range.
std::size_t segment_of(const std::vector<PiecewiseLinear::Point>& points, double x) {
  auto it = std::upper_bound(points.begin(), points.end(), x,
                             [](double v, const PiecewiseLinear::Point& p) { return v < p.x; });
  return static_cast<std::size_t>(it - points.begin()) - 1;
}

}  // namespace

double PiecewiseLinear::operator()(double x) const {
  if (points_.empty()) return 0.0;
  if (x <= points_.front().x) return points_.front().y;
  if (x >= points_.back().x) return points_.back().y;
  const std::size_t i = segment_of(points_, x);
  const Point& a = points_[i];
  const Point& b = points_[i + 1];
  if (b.x <= a.x) return b.y;
  return a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x);
}

double PiecewiseLinear::slope(double x) const {
  if (points_.size() < 2 || x < points_.front().x || x >= points_.back().x) return 0.0;
  const std::size_t i = segment_of(points_, x);
  const Point& a = points_[i];
  const Point& b = points_[i + 1];
  if (b.x <= a.x) return 0.0;
  return (b.y - a.y) / (b.x - a.x);
}

std::string PiecewiseLinear::validate(const std::string& name) const {
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (!std::isfinite(points_[i].x) || !std::isfinite(points_[i].y)) {
      return name + ": breakpoint " + std::to_string(i) + " is not finite";
    }
    if (i > 0 && points_[i].x < points_[i - 1].x) {
      return name + ": breakpoint " + std::to_string(i) + " goes back in x";
    }
  }
  return "";
}

}  // namespace vmass::sim
