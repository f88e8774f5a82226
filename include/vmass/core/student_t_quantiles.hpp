// StudentTQuantiles: the Student-t quantile at one probability, for any number of degrees of
// freedom, remembered for the last kSlots values of the dof it was asked for.
//
// Boost.Math inverts the t distribution in long double (tens of microseconds). The Bayes
// posterior needs the quantile each time its shape changes, and the pipeline asks copies of
// the same posterior (the open batch closed, the pairs held for the driveline lag) for the
// same shapes tick after tick, although most ticks accept no pair. A remembered value is the
// value computed for exactly that dof: the published numbers do not move.
//
// Counts its evaluations and lookups (tests bound them per tick: tests/core). Pure; not
// thread-safe (one estimator's copies share one instance on one thread); no allocation.
#pragma once

#include <array>
#include <cstdint>

namespace vmass {

class StudentTQuantiles {
 public:
  static constexpr int kSlots = 16;

  /// The quantile at `probability` in (0, 1).
  explicit StudentTQuantiles(double probability);

  /// The quantile for `dof` degrees of freedom; NaN when dof is not finite and > 0 or Boost
  /// cannot evaluate it.
  double at(double dof);

  std::int64_t evaluations() const { return evaluations_; }  ///< computed by Boost.Math
  std::int64_t lookups() const { return lookups_; }

 private:
  double probability_;
  std::array<double, kSlots> dof_{};
  std::array<double, kSlots> value_{};
  int used_ = 0;
  int next_ = 0;  ///< the slot the next new dof replaces (round robin)
  std::int64_t evaluations_ = 0;
  std::int64_t lookups_ = 0;
};

}  // namespace vmass
