// PiecewiseLinear: a function y(x) given by breakpoints, linearly interpolated between them and
// held constant before the first and after the last breakpoint. The simulator uses it for road
// profiles (grade over distance) and driver references (speed over time).
//
//   y(x) = y_i + (y_{i+1} - y_i) (x - x_i) / (x_{i+1} - x_i)   for x_i <= x < x_{i+1}
//
// Value type; const member functions are safe to call from several threads.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace vmass::sim {

class PiecewiseLinear {
 public:
  struct Point {
    double x = 0.0;
    double y = 0.0;
  };

  PiecewiseLinear() = default;
  /// A constant function.
  explicit PiecewiseLinear(double constant) : points_{{0.0, constant}} {}
  /// Breakpoints in non-decreasing x (a repeated x makes a step).
  explicit PiecewiseLinear(std::vector<Point> points) : points_(std::move(points)) {}

  /// y(x); 0 when there are no breakpoints.
  double operator()(double x) const;
  /// dy/dx at x (right derivative; 0 outside the breakpoints).
  double slope(double x) const;

  const std::vector<Point>& points() const { return points_; }
  bool empty() const { return points_.empty(); }

  /// "" or a message when the breakpoints are not finite or not in non-decreasing x.
  std::string validate(const std::string& name) const;

 private:
  std::vector<Point> points_;
};

}  // namespace vmass::sim
