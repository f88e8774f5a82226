#include "vmass/baselines/nig_regression.hpp"

#include <cmath>

#include <Eigen/Cholesky>
#include <boost/math/distributions/students_t.hpp>

namespace vmass::baselines {

NigRegression::NigRegression(const NigPrior& prior, int batch_size)
    : batch_size_(batch_size < 1 ? 1 : batch_size), mean_(prior.mean) {
  const double s2 = prior.noise_std_guess * prior.noise_std_guess;
  v_ = (prior.std.cwiseProduct(prior.std) / s2).asDiagonal();
  shape_ = 0.5 * prior.noise_dof;
  scale_ = shape_ * s2;
}

bool NigRegression::add(double y, const Eigen::RowVector2d& phi) {
  if (!std::isfinite(y) || !phi.allFinite()) return false;
  const double e = y - (phi * mean_)(0, 0);
  phi_t_phi_ += phi.transpose() * phi;
  phi_t_e_ += phi.transpose() * e;
  e_t_e_ += e * e;
  if (++pending_ < batch_size_) return false;
  close_batch();
  return true;
}

void NigRegression::close_batch() {
  const Eigen::Matrix2d info = v_.ldlt().solve(Eigen::Matrix2d::Identity()) + phi_t_phi_;
  Eigen::Matrix2d v = info.ldlt().solve(Eigen::Matrix2d::Identity());
  v = 0.5 * (v + v.transpose()).eval();
  const Eigen::Vector2d shift = v * phi_t_e_;
  const double shape = shape_ + 0.5 * pending_;
  const double scale = scale_ + 0.5 * (e_t_e_ - phi_t_e_.dot(shift));
  const Eigen::Vector2d mean = mean_ + shift;
  if (mean.allFinite() && v.allFinite() && std::isfinite(scale) && scale > 0.0) {
    mean_ = mean;
    v_ = v;
    shape_ = shape;
    scale_ = scale;
    pairs_used_ += pending_;
    ++batches_;
  }
  phi_t_phi_.setZero();
  phi_t_e_.setZero();
  e_t_e_ = 0.0;
  pending_ = 0;
}

void NigRegression::mass_interval(double level, double* low, double* high) const {
  using NoThrow = boost::math::policies::policy<
      boost::math::policies::domain_error<boost::math::policies::ignore_error>,
      boost::math::policies::overflow_error<boost::math::policies::ignore_error>>;
  const boost::math::students_t_distribution<double, NoThrow> t(2.0 * shape_);
  const double q = boost::math::quantile(t, 0.5 * (1.0 + level));
  const double half_width = q * std::sqrt(scale_ / shape_ * v_(0, 0));
  *low = mean_[0] - half_width;
  *high = mean_[0] + half_width;
}

}  // namespace vmass::baselines
