#include "vmass/core/student_t_quantiles.hpp"

#include <cmath>
#include <limits>

#include <boost/math/distributions/students_t.hpp>

namespace vmass {

namespace {

// Boost.Math reports errors through the policy instead of throwing: the core never throws.
using NoThrowPolicy = boost::math::policies::policy<
    boost::math::policies::domain_error<boost::math::policies::ignore_error>,
    boost::math::policies::pole_error<boost::math::policies::ignore_error>,
    boost::math::policies::overflow_error<boost::math::policies::ignore_error>,
    boost::math::policies::evaluation_error<boost::math::policies::ignore_error>>;

}  // namespace

StudentTQuantiles::StudentTQuantiles(double probability) : probability_(probability) {}

double StudentTQuantiles::at(double dof) {
  ++lookups_;
  if (!(std::isfinite(dof) && dof > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < used_; ++i) {
    if (dof_[static_cast<std::size_t>(i)] == dof) return value_[static_cast<std::size_t>(i)];
  }
  ++evaluations_;
  const double t = boost::math::quantile(
      boost::math::students_t_distribution<double, NoThrowPolicy>(dof), probability_);
  const auto slot = static_cast<std::size_t>(next_);
  dof_[slot] = dof;
  value_[slot] = t;
  next_ = (next_ + 1) % kSlots;
  if (used_ < kSlots) ++used_;
  return t;
}

}  // namespace vmass
