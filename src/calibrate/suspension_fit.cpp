// The rear-suspension fit of suspension_fit.hpp. The only translation unit of the library that
// includes Ceres.
#include "vmass/calibrate/suspension_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include <ceres/ceres.h>
#include <Eigen/Dense>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/students_t.hpp>

#include "vmass/calibrate/suspension_residuals.hpp"
#include "vmass/core/param_check.hpp"

namespace vmass::calibrate {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMinStiffnessNPerMm = 1e-6;
constexpr int kMaxRobustPasses = 6;

// Step data in the fit's units (mm, N), sorted by load.
struct Data {
  std::vector<double> force_n;
  std::vector<double> z_mm;
  std::vector<double> se2_mm2;  ///< squared standard error of each step mean (0: one sample)
  std::size_t size() const { return z_mm.size(); }
};

struct LinearParams {
  double z0_mm = 0.0;
  double c_n_per_mm = 1.0;
};

struct ProgressiveParams {
  double z0_mm = 0.0;
  double c_n_per_mm = 1.0;
  double d_mm = 0.0;  ///< knee offset above z0
  double k2_n_per_mm2 = 0.0;
};

// Outcome of one solve.
struct Solve {
  bool usable = false;
  double cost = 0.0;
  int iterations = 0;
  std::string termination;
};

ceres::Solver::Options solver_options() {
  ceres::Solver::Options o;
  o.linear_solver_type = ceres::DENSE_QR;
  o.minimizer_type = ceres::TRUST_REGION;
  o.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  o.max_num_iterations = 200;
  o.function_tolerance = 1e-14;
  o.gradient_tolerance = 1e-14;
  o.parameter_tolerance = 1e-12;
  o.logging_type = ceres::SILENT;
  o.minimizer_progress_to_stdout = false;
  o.num_threads = 1;
  return o;
}

ceres::LossFunction* cauchy(double scale_mm) {
  return scale_mm > 0.0 ? new ceres::CauchyLoss(scale_mm) : nullptr;
}

// Fills *cov with the unscaled (J^T J)^-1 of the problem at its current parameter values, in
// the order of `blocks`. False when Ceres finds it rank deficient.
bool covariance_of(ceres::Problem* problem, const std::vector<const double*>& blocks,
                   Eigen::MatrixXd* cov) {
  ceres::Covariance::Options co;
  co.algorithm_type = ceres::DENSE_SVD;
  ceres::Covariance covariance(co);
  std::vector<std::pair<const double*, const double*>> pairs;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    for (std::size_t j = i; j < blocks.size(); ++j) pairs.emplace_back(blocks[i], blocks[j]);
  }
  if (!covariance.Compute(pairs, problem)) return false;
  const int p = static_cast<int>(blocks.size());
  cov->resize(p, p);
  if (!covariance.GetCovarianceMatrix(blocks, cov->data())) return false;
  return cov->allFinite();
}

void finish(ceres::Problem* problem, Solve* out) {
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options(), problem, &summary);
  out->usable = summary.IsSolutionUsable();
  out->cost = summary.final_cost;
  out->iterations = static_cast<int>(summary.iterations.size());
  out->termination = ceres::TerminationTypeToString(summary.termination_type);
}

Solve solve_linear(const Data& data, const std::vector<std::size_t>& idx, double scale_mm,
                   LinearParams* p) {
  ceres::Problem problem;
  for (std::size_t k : idx) {
    problem.AddResidualBlock(LinearDeflectionResidual::Create(data.force_n[k], data.z_mm[k]),
                             cauchy(scale_mm), &p->z0_mm, &p->c_n_per_mm);
  }
  problem.SetParameterLowerBound(&p->c_n_per_mm, 0, kMinStiffnessNPerMm);
  Solve out;
  finish(&problem, &out);
  return out;
}

Solve solve_progressive(const Data& data, double scale_mm, bool knee_fixed, ProgressiveParams* p) {
  ceres::Problem problem;
  for (std::size_t k = 0; k < data.size(); ++k) {
    problem.AddResidualBlock(ProgressiveDeflectionResidual::Create(data.force_n[k], data.z_mm[k]),
                             cauchy(scale_mm), &p->z0_mm, &p->c_n_per_mm, &p->d_mm,
                             &p->k2_n_per_mm2);
  }
  problem.SetParameterLowerBound(&p->c_n_per_mm, 0, kMinStiffnessNPerMm);
  problem.SetParameterLowerBound(&p->k2_n_per_mm2, 0, 0.0);
  if (knee_fixed) {
    problem.SetParameterBlockConstant(&p->d_mm);
  } else {
    problem.SetParameterLowerBound(&p->d_mm, 0, 0.0);
  }
  Solve out;
  finish(&problem, &out);
  return out;
}

double linear_prediction(const LinearParams& p, double force_n) {
  return p.z0_mm + force_n / p.c_n_per_mm;
}

double progressive_prediction(const ProgressiveParams& p, double force_n) {
  return ProgressiveDeflectionResidual::predicted_deflection_mm(force_n, p.z0_mm, p.c_n_per_mm,
                                                                p.d_mm, p.k2_n_per_mm2);
}

double median_abs(const std::vector<double>& r) {
  std::vector<double> a(r.size());
  std::transform(r.begin(), r.end(), a.begin(), [](double x) { return std::abs(x); });
  if (a.empty()) return 0.0;
  std::sort(a.begin(), a.end());
  const std::size_t m = a.size() / 2;
  return a.size() % 2 ? a[m] : 0.5 * (a[m - 1] + a[m]);
}

// 3 robust sigmas: 1.4826 median|r|, corrected for the p parameters the fit absorbed.
double next_scale(const std::vector<double>& residuals, int parameters,
                  const SuspensionFitOptions& o) {
  const double n = static_cast<double>(residuals.size());
  const double absorbed = n > parameters ? std::sqrt(n / (n - parameters)) : 1.0;
  return std::max(o.min_robust_scale_mm, 3.0 * 1.4826 * median_abs(residuals) * absorbed);
}

double cauchy_weight(double r, double scale_mm) {
  return scale_mm > 0.0 ? 1.0 / (1.0 + (r / scale_mm) * (r / scale_mm)) : 1.0;
}

// Closed-form least squares of the linear model in force space, F = c (z - z0), over idx: the
// starting point of the Ceres fits.
LinearParams linear_start(const Data& d, const std::vector<std::size_t>& idx) {
  double sz = 0, sf = 0, szz = 0, szf = 0;
  for (std::size_t k : idx) {
    sz += d.z_mm[k];
    sf += d.force_n[k];
    szz += d.z_mm[k] * d.z_mm[k];
    szf += d.z_mm[k] * d.force_n[k];
  }
  const double n = static_cast<double>(idx.size());
  const double den = n * szz - sz * sz;
  LinearParams p;
  p.c_n_per_mm = den > 0.0 ? (n * szf - sz * sf) / den : 1.0;
  if (!(p.c_n_per_mm > kMinStiffnessNPerMm)) p.c_n_per_mm = 1.0;
  p.z0_mm = (sz - sf / p.c_n_per_mm) / n;
  return p;
}

// Closed-form force-space least squares with the knee at an absolute position: F = c z - c z0
// + k2 max(0, z - knee)^2 is linear in (c, c z0, k2). Starting point of a grid solve.
bool progressive_start(const Data& d, double knee_mm, ProgressiveParams* p) {
  const int n = static_cast<int>(d.size());
  Eigen::MatrixXd a(n, 3);
  Eigen::VectorXd f(n);
  for (int k = 0; k < n; ++k) {
    const double z = d.z_mm[static_cast<std::size_t>(k)];
    const double h = std::max(0.0, z - knee_mm);
    a(k, 0) = z;
    a(k, 1) = -1.0;
    a(k, 2) = h * h;
    f(k) = d.force_n[static_cast<std::size_t>(k)];
  }
  const Eigen::Vector3d x = a.colPivHouseholderQr().solve(f);
  if (!x.allFinite() || !(x(0) > kMinStiffnessNPerMm)) return false;
  p->c_n_per_mm = x(0);
  p->z0_mm = x(1) / x(0);
  p->k2_n_per_mm2 = std::max(0.0, x(2));
  p->d_mm = knee_mm - p->z0_mm;
  return p->d_mm >= 0.0;
}

struct Uncertainty {
  double residual_std = kNaN;  ///< s from the residuals
  double step_se = 0.0;        ///< RMS standard error of the step means (0: unknown)
  double scale = kNaN;         ///< max(residual_std, step_se): what the covariance is scaled by
  double dof = 0.0;
  double t = kNaN;
};

// step_se2: the step means' squared standard errors (0 when a step has one sample).
Uncertainty uncertainty(const std::vector<double>& residuals, const std::vector<double>& step_se2,
                        double scale_mm, int parameters, double confidence) {
  double sw = 0.0, swr2 = 0.0, swse2 = 0.0;
  for (std::size_t k = 0; k < residuals.size(); ++k) {
    const double w = cauchy_weight(residuals[k], scale_mm);
    sw += w;
    swr2 += w * residuals[k] * residuals[k];
    swse2 += w * step_se2[k];
  }
  Uncertainty u;
  u.dof = sw - parameters;
  if (sw > 0.0) u.step_se = std::sqrt(swse2 / sw);
  if (u.dof < 0.5) return u;
  u.residual_std = std::sqrt(swr2 / u.dof);
  u.scale = std::max(u.residual_std, u.step_se);
  u.t = boost::math::quantile(boost::math::students_t(u.dof), 0.5 * (1.0 + confidence));
  return u;
}

Estimate estimate(double value, double variance_unscaled, const Uncertainty& u, double to_si,
                  bool covariance_ok) {
  Estimate e;
  e.value = value * to_si;
  if (!covariance_ok || !std::isfinite(u.scale) || !(variance_unscaled >= 0.0)) return e;
  e.std = std::sqrt(variance_unscaled) * u.scale * to_si;
  e.low = e.value - u.t * e.std;
  e.high = e.value + u.t * e.std;
  return e;
}

std::string fmt(const char* format, double v) {
  char buf[128];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// The reported parameters of each model, as ParameterCovariance names them.
std::vector<std::string> linear_names() { return {"stiffness_n_per_m", "zero_offset_m"}; }
std::vector<std::string> progressive_names() {
  return {"stiffness_n_per_m", "zero_offset_m", "knee_m", "rate_n_per_m2"};
}

// The reported parameters' covariance in SI units, s^2 A C A^T (parameter_covariance.hpp): c
// the unscaled covariance of the fitted parameters (valid when computed), a the Jacobian of the
// reported parameters with respect to the fitted ones.
ParameterCovariance reported_covariance(std::vector<std::string> names, bool computed,
                                        const Eigen::MatrixXd& c, const Eigen::MatrixXd& a,
                                        const Uncertainty& u) {
  if (!computed) {
    return not_estimable_covariance(
        std::move(names),
        "rank deficient: Ceres could not invert J^T J at the solution (reciprocal condition "
        "number below 1e-14): the steps do not determine every parameter");
  }
  if (!std::isfinite(u.scale)) {
    return not_estimable_covariance(
        std::move(names),
        "no residual degree of freedom to scale it by (effective dof " + fmt("%.2f", u.dof) + ")");
  }
  const Eigen::MatrixXd sigma = u.scale * u.scale * a * c * a.transpose();
  std::vector<double> row_major;
  for (int i = 0; i < sigma.rows(); ++i) {
    for (int j = 0; j < sigma.cols(); ++j) row_major.push_back(sigma(i, j));
  }
  return make_parameter_covariance(std::move(names), row_major);
}

}  // namespace

std::string SuspensionFitOptions::validate() const {
  ParamCheck c("fit");
  c.in_open_range("linear_tolerance", linear_tolerance, 0.0, 1.0);
  c.non_negative("robust_scale_mm", robust_scale_mm);
  c.positive("min_robust_scale_mm", min_robust_scale_mm);
  c.at_least("knee_grid_per_gap", knee_grid_per_gap, 1);
  c.at_least("min_steps_below_knee", min_steps_below_knee, 3);
  c.at_least("min_steps_beyond_knee", min_steps_beyond_knee, 2);
  c.in_open_range("progressive_significance", progressive_significance, 0.0, 1.0);
  c.in_open_range("confidence", confidence, 0.0, 1.0);
  return c.message();
}

SuspensionParams SuspensionCalibration::linear_suspension_params() const {
  SuspensionParams s;
  s.stiffness_n_per_m = linear.stiffness_n_per_m.value;
  s.empty_deflection_m = linear.zero_offset_m.value;
  s.linear_range_kg = linear_range_kg;
  s.calibrated_range_kg = calibrated_range_kg;
  return s;
}

SuspensionParams SuspensionCalibration::suspension_params() const {
  if (!progressive.detected) return linear_suspension_params();
  SuspensionParams s;
  s.stiffness_n_per_m = progressive.stiffness_n_per_m.value;
  s.empty_deflection_m = progressive.zero_offset_m.value;
  s.progressive_knee_m = progressive.knee_m.value;
  s.progressive_rate_n_per_m2 = progressive.rate_n_per_m2.value;
  s.linear_range_kg = linear_range_kg;
  s.calibrated_range_kg = calibrated_range_kg;
  return s;
}

namespace {

/// What every stage of the fit reads: the sorted steps as data, and the options.
struct FitInput {
  const Data& data;
  const SuspensionFitOptions& options;
  std::vector<std::size_t> all;  ///< indices of every step
  double first_scale = 0.0;      ///< the robust scale's first guess, mm
  bool fixed_scale = false;      ///< --robust-scale-mm given
  std::size_t size() const { return data.size(); }
  double start_scale() const { return fixed_scale ? options.robust_scale_mm : first_scale; }
};

struct ProgressiveRun {
  ProgressiveParams params;
  bool usable = false;
  double scale_mm = 0.0;
  Solve solve;
};

/// The best knee on a grid over the gaps between steps (the knee held), at one robust scale.
bool best_knee_on_grid(const FitInput& in, double scale_mm, ProgressiveParams* best) {
  const std::size_t below = static_cast<std::size_t>(in.options.min_steps_below_knee);
  const std::size_t beyond = static_cast<std::size_t>(in.options.min_steps_beyond_knee);
  const Data& data = in.data;
  bool found = false;
  double best_cost = std::numeric_limits<double>::infinity();
  for (std::size_t j = below; j + beyond <= in.size(); ++j) {  // knee between steps j-1 and j
    for (int g = 0; g < in.options.knee_grid_per_gap; ++g) {
      const double knee_mm = data.z_mm[j - 1] + (g + 0.5) / in.options.knee_grid_per_gap *
                                                    (data.z_mm[j] - data.z_mm[j - 1]);
      ProgressiveParams p;
      if (!progressive_start(data, knee_mm, &p)) {
        const LinearParams l =
            linear_start(data, std::vector<std::size_t>(in.all.begin(), in.all.begin() + j));
        p.z0_mm = l.z0_mm;
        p.c_n_per_mm = l.c_n_per_mm;
        p.d_mm = std::max(0.0, knee_mm - l.z0_mm);
        p.k2_n_per_mm2 = 0.0;
      }
      const Solve s = solve_progressive(data, scale_mm, true, &p);
      if (s.usable && s.cost < best_cost) {
        best_cost = s.cost;
        *best = p;
        found = true;
      }
    }
  }
  return found;
}

std::vector<double> progressive_residuals_mm(const Data& data, const ProgressiveParams& p) {
  std::vector<double> r(data.size());
  for (std::size_t k = 0; k < data.size(); ++k) {
    r[k] = data.z_mm[k] - progressive_prediction(p, data.force_n[k]);
  }
  return r;
}

/// The progressive model: knee on a grid, then all four parameters refined; the robust scale
/// re-estimated until it settles. Says why not in *reason when it cannot be fitted.
ProgressiveRun fit_progressive(const FitInput& in, std::string* reason) {
  ProgressiveRun run;
  run.scale_mm = in.start_scale();
  const int below = in.options.min_steps_below_knee, beyond = in.options.min_steps_beyond_knee;
  if (in.size() < static_cast<std::size_t>(below) + static_cast<std::size_t>(beyond)) {
    *reason = "needs at least " + std::to_string(below + beyond) +
              " steps (fit.min_steps_below_knee + fit.min_steps_beyond_knee)";
    return run;
  }
  for (int pass = 0;; ++pass) {
    ProgressiveParams best;
    if (!best_knee_on_grid(in, run.scale_mm, &best)) {
      run.usable = false;
      *reason = "no knee candidate gave a usable fit";
      return run;
    }
    run.params = best;
    run.solve = solve_progressive(in.data, run.scale_mm, false, &run.params);
    run.usable = run.solve.usable;
    if (!run.usable) {
      *reason = "Ceres could not make the progressive fit usable (" + run.solve.termination + ")";
      return run;
    }
    if (in.fixed_scale || pass + 1 == kMaxRobustPasses) return run;
    const double next = next_scale(progressive_residuals_mm(in.data, run.params), 4, in.options);
    if (std::abs(next - run.scale_mm) <= 0.1 * run.scale_mm) return run;
    run.scale_mm = next;
  }
}

/// Is the bump stop real? Against the linear model over all steps at the same robust scale
/// (F test), with enough steps beyond the knee and a visible effect on the top step. Sets
/// pf->detected, or pf->reason.
void judge_progressive(const FitInput& in, const ProgressiveRun& run, ProgressiveFit* pf) {
  const Data& data = in.data;
  const ProgressiveParams& prog = run.params;
  LinearParams lin_all = linear_start(data, in.all);
  const Solve lin_all_solve = solve_linear(data, in.all, run.scale_mm, &lin_all);
  const double knee_mm = prog.z0_mm + prog.d_mm;
  const long steps_beyond =
      std::count_if(data.z_mm.begin(), data.z_mm.end(), [&](double z) { return z > knee_mm; });
  const double top_n = data.force_n.back();
  if (!lin_all_solve.usable) {
    pf->reason = "the linear comparison fit failed (" + lin_all_solve.termination + ")";
  } else if (!(prog.k2_n_per_mm2 > 0.0)) {
    pf->reason = "the best progressive rate is 0 (no bump stop in the data)";
  } else if (steps_beyond < static_cast<long>(in.options.min_steps_beyond_knee)) {
    pf->reason = "only " + std::to_string(steps_beyond) + " step(s) beyond the fitted knee";
  } else if (prog.z0_mm + top_n / prog.c_n_per_mm - progressive_prediction(prog, top_n) <=
             2.0 * run.scale_mm) {
    pf->reason =
        "the fitted bump stop changes the top step's deflection by less than twice "
        "the robust scale";
  } else {
    const double dof2 = static_cast<double>(in.size()) - 4.0;
    const double cost = run.solve.cost, lin_cost = lin_all_solve.cost;
    pf->f_statistic = cost > 0.0 ? ((lin_cost - cost) / 2.0) / (cost / dof2)
                                 : (lin_cost > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
    pf->f_critical = boost::math::quantile(boost::math::fisher_f(2.0, dof2),
                                           1.0 - in.options.progressive_significance);
    if (pf->f_statistic > pf->f_critical) {
      pf->detected = true;
    } else {
      pf->reason = "the progressive model is not significantly better than the linear one (F = " +
                   fmt("%.3g", pf->f_statistic) + " <= " + fmt("%.3g", pf->f_critical) + ")";
    }
  }
}

/// The progressive fit's statistics, significance and, for an accepted bump stop, its
/// parameters' uncertainty (without one, d and k2 are not identifiable).
void describe_progressive(const FitInput& in, const ProgressiveRun& run,
                          SuspensionCalibration* cal) {
  const Data& data = in.data;
  const ProgressiveParams& prog = run.params;
  const Uncertainty u = uncertainty(progressive_residuals_mm(data, prog), data.se2_mm2,
                                    run.scale_mm, 4, in.options.confidence);
  ProgressiveFit& pf = cal->progressive;
  pf.stats = {static_cast<int>(in.size()),
              run.scale_mm,
              u.residual_std,
              u.step_se,
              u.dof,
              run.solve.cost,
              run.solve.iterations,
              run.solve.termination};
  judge_progressive(in, run, &pf);
  Eigen::MatrixXd c;
  bool ok = false;
  if (pf.detected) {
    ProgressiveParams at = prog;
    ceres::Problem problem;
    for (std::size_t k = 0; k < in.size(); ++k) {
      problem.AddResidualBlock(ProgressiveDeflectionResidual::Create(data.force_n[k], data.z_mm[k]),
                               cauchy(run.scale_mm), &at.z0_mm, &at.c_n_per_mm, &at.d_mm,
                               &at.k2_n_per_mm2);
    }
    ok = covariance_of(&problem, {&at.z0_mm, &at.c_n_per_mm, &at.d_mm, &at.k2_n_per_mm2}, &c);
    if (!ok) cal->warnings.push_back("the progressive model's covariance is singular");
  }
  pf.zero_offset_m = estimate(prog.z0_mm, ok ? c(0, 0) : kNaN, u, 1e-3, ok);
  pf.stiffness_n_per_m = estimate(prog.c_n_per_mm, ok ? c(1, 1) : kNaN, u, 1e3, ok);
  // z_knee = z0 + d: var = var z0 + var d + 2 cov(z0, d).
  pf.knee_m =
      estimate(prog.z0_mm + prog.d_mm, ok ? c(0, 0) + c(2, 2) + 2.0 * c(0, 2) : kNaN, u, 1e-3, ok);
  pf.rate_n_per_m2 = estimate(prog.k2_n_per_mm2, ok ? c(3, 3) : kNaN, u, 1e6, ok);
  if (!pf.detected) {
    pf.covariance = not_estimable_covariance(
        progressive_names(), "without a bump stop the knee and rate are not identified");
    return;
  }
  // Fitted (z0 mm, c N/mm, d mm, k2 N/mm^2) to reported (c N/m, z0 m, z0 + d m, k2 N/m^2).
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(4, 4);
  a(0, 1) = 1e3;
  a(1, 0) = 1e-3;
  a(2, 0) = 1e-3;
  a(2, 2) = 1e-3;
  a(3, 3) = 1e6;
  pf.covariance = reported_covariance(progressive_names(), ok, c, a, u);
}

struct LinearRun {
  std::vector<std::size_t> steps;  ///< the steps at or below the knee
  LinearParams params;
  double scale_mm = 0.0;
  Solve solve;
};

/// The linear model on the steps at or below the knee, the robust scale re-estimated.
LinearRun fit_linear(const FitInput& in, double knee_mm) {
  LinearRun run;
  for (std::size_t k = 0; k < in.size(); ++k) {
    if (in.data.z_mm[k] <= knee_mm) run.steps.push_back(k);
  }
  run.params = linear_start(in.data, run.steps);
  run.scale_mm = in.start_scale();
  for (int pass = 0;; ++pass) {
    run.solve = solve_linear(in.data, run.steps, run.scale_mm, &run.params);
    if (!run.solve.usable || in.fixed_scale || pass + 1 == kMaxRobustPasses) break;
    std::vector<double> r;
    for (std::size_t k : run.steps) {
      r.push_back(in.data.z_mm[k] - linear_prediction(run.params, in.data.force_n[k]));
    }
    const double next = next_scale(r, 2, in.options);
    if (std::abs(next - run.scale_mm) <= 0.1 * run.scale_mm) break;
    run.scale_mm = next;
  }
  return run;
}

/// The linear fit's parameters with their uncertainty, and its statistics.
void describe_linear(const FitInput& in, const LinearRun& run, SuspensionCalibration* cal) {
  std::vector<double> r, se2;
  for (std::size_t k : run.steps) {
    r.push_back(in.data.z_mm[k] - linear_prediction(run.params, in.data.force_n[k]));
    se2.push_back(in.data.se2_mm2[k]);
  }
  const Uncertainty u = uncertainty(r, se2, run.scale_mm, 2, in.options.confidence);
  Eigen::MatrixXd c;
  LinearParams at = run.params;
  ceres::Problem problem;
  for (std::size_t k : run.steps) {
    problem.AddResidualBlock(LinearDeflectionResidual::Create(in.data.force_n[k], in.data.z_mm[k]),
                             cauchy(run.scale_mm), &at.z0_mm, &at.c_n_per_mm);
  }
  const bool ok = covariance_of(&problem, {&at.z0_mm, &at.c_n_per_mm}, &c);
  LinearFit& lf = cal->linear;
  lf.zero_offset_m = estimate(run.params.z0_mm, ok ? c(0, 0) : kNaN, u, 1e-3, ok);
  lf.stiffness_n_per_m = estimate(run.params.c_n_per_mm, ok ? c(1, 1) : kNaN, u, 1e3, ok);
  // Fitted (z0 mm, c N/mm) to reported (c N/m, z0 m).
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2, 2);
  a(0, 1) = 1e3;
  a(1, 0) = 1e-3;
  lf.covariance = reported_covariance(linear_names(), ok, c, a, u);
  lf.stats = {static_cast<int>(run.steps.size()),
              run.scale_mm,
              u.residual_std,
              u.step_se,
              u.dof,
              run.solve.cost,
              run.solve.iterations,
              run.solve.termination};
  if (!std::isfinite(lf.stiffness_n_per_m.std)) {
    cal->warnings.push_back(
        "the linear stiffness's standard deviation is not estimable (too few steps below the "
        "knee, or a singular covariance)");
  }
}

/// Per step: residuals, outliers, the linear model's mass error.
void describe_steps(const FitInput& in, const std::vector<BallastStep>& steps,
                    const ProgressiveRun& prog, const LinearRun& lin, double knee_mm,
                    SuspensionCalibration* cal) {
  const Data& data = in.data;
  const double per_kg = cal->geometry.wheel_force_per_kg();
  const bool detected = cal->progressive.detected;
  for (std::size_t k = 0; k < in.size(); ++k) {
    BallastStepFit s;
    s.step = steps[k];
    s.force_n = data.force_n[k];
    s.linear_residual_m = (data.z_mm[k] - linear_prediction(lin.params, data.force_n[k])) * 1e-3;
    if (prog.usable) {
      s.progressive_residual_m =
          (data.z_mm[k] - progressive_prediction(prog.params, data.force_n[k])) * 1e-3;
    }
    s.in_linear_fit = data.z_mm[k] <= knee_mm;
    const double residual_mm = (detected ? s.progressive_residual_m : s.linear_residual_m) * 1e3;
    s.outlier = std::abs(residual_mm) > 2.0 * (detected ? prog.scale_mm : lin.scale_mm);
    const double m = steps[k].added_mass_kg;
    const double m_lin = lin.params.c_n_per_mm * (data.z_mm[k] - lin.params.z0_mm) / per_kg;
    s.linear_mass_error = m != 0.0 ? (m_lin - m) / std::abs(m) : 0.0;
    if (s.outlier) {
      cal->warnings.push_back("step " + fmt("%g kg", m) + " is an outlier (residual " +
                              fmt("%.3f mm", residual_mm) + "); the robust loss down-weighted it");
    }
    cal->steps.push_back(s);
  }
}

/// The linear range (the heaviest step up to which the linear model is within tolerance) and
/// the calibrated range, with their warnings.
void set_ranges(const std::vector<BallastStep>& steps, const SuspensionFitOptions& options,
                SuspensionCalibration* cal) {
  cal->calibrated_range_kg = steps.back().added_mass_kg;
  cal->linear_range_kg = 0.0;
  for (const BallastStepFit& s : cal->steps) {
    if (s.step.added_mass_kg <= 0.0 || s.outlier) continue;
    if (std::abs(s.linear_mass_error) > options.linear_tolerance) break;
    cal->linear_range_kg = s.step.added_mass_kg;
  }
  if (!(cal->linear_range_kg > 0.0)) {
    cal->warnings.push_back("no ballast step is reproduced by the linear model within " +
                            fmt("%g %%", 100.0 * options.linear_tolerance));
  }
  if (!cal->progressive.detected && !cal->progressive.reason.empty()) {
    cal->warnings.push_back("no bump stop: " + cal->progressive.reason);
  }
}

Data to_data(const std::vector<BallastStep>& steps, const LoadGeometry& geometry) {
  Data data;
  for (const BallastStep& s : steps) {
    data.force_n.push_back(geometry.wheel_force_n(s.added_mass_kg));
    data.z_mm.push_back(s.deflection_m * 1e3);
    const double se_mm =
        s.sample_count > 1 ? s.deflection_std_m * 1e3 / std::sqrt(s.sample_count) : 0.0;
    data.se2_mm2.push_back(std::isfinite(se_mm) ? se_mm * se_mm : 0.0);
  }
  return data;
}

}  // namespace

SuspensionFitResult fit_suspension(const std::vector<BallastStep>& input_steps,
                                   const LoadGeometry& geometry,
                                   const SuspensionFitOptions& options) {
  SuspensionFitResult result;
  for (const std::string& m : {options.validate(), geometry.validate(), check_steps(input_steps)}) {
    if (!m.empty()) {
      result.error = m;
      return result;
    }
  }
  std::vector<BallastStep> steps = input_steps;
  std::stable_sort(steps.begin(), steps.end(), [](const BallastStep& a, const BallastStep& b) {
    return a.added_mass_kg < b.added_mass_kg;
  });
  const Data data = to_data(steps, geometry);
  FitInput in{data, options, std::vector<std::size_t>(data.size()), 0.0,
              options.robust_scale_mm > 0.0};
  std::iota(in.all.begin(), in.all.end(), 0);
  in.first_scale =
      std::max(options.min_robust_scale_mm, 0.01 * (data.z_mm.back() - data.z_mm.front()));

  SuspensionCalibration cal;
  cal.geometry = geometry;
  cal.linear_tolerance = options.linear_tolerance;
  const ProgressiveRun prog = fit_progressive(in, &cal.progressive.reason);
  if (prog.usable) {
    describe_progressive(in, prog, &cal);
  } else {
    cal.progressive.covariance =
        not_estimable_covariance(progressive_names(), "no usable progressive fit");
  }
  const double knee_mm = cal.progressive.detected ? prog.params.z0_mm + prog.params.d_mm
                                                  : std::numeric_limits<double>::infinity();
  const LinearRun lin = fit_linear(in, knee_mm);
  if (!lin.solve.usable) {
    result.error = "Ceres could not make the linear fit usable (" + lin.solve.termination + ")";
    return result;
  }
  describe_linear(in, lin, &cal);
  describe_steps(in, steps, prog, lin, knee_mm, &cal);
  set_ranges(steps, options, &cal);
  result.calibration = std::move(cal);
  return result;
}

}  // namespace vmass::calibrate
