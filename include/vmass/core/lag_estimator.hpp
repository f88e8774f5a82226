// LagEstimator: identifies from the data how long the measured acceleration lags the force
// signal (the ECU reports its torque before the hub sees it: actuation, the driveline's mode,
// the ESC's filtering of a_x, the messages' different latencies), so that the longitudinal
// block pairs the acceleration with the force of the same instant.
//
// The longitudinal block hands it every excited pair twice over: the differenced acceleration
// da, and the differenced force y(L) = dF(k - L) - m_rot dv' at each candidate lag L = 0 ..
// max_lag_ticks (the same filtered force, taken L ticks earlier). For each L it keeps the
// regression statistics with exponential forgetting (memory_s of pairs):
//   S_aa <- lambda S_aa + da^2,   S_ay(L) <- lambda S_ay(L) + da y(L),   S_yy(L) likewise
// and the lag is the L whose pairs fit the model y = M da best: the largest correlation
// rho(L) = S_ay / sqrt(S_aa S_yy), refined to a fraction of a tick by a parabola through the
// peak. This targets exactly what biases the mass (a misalignment of 10 ms moves it by about
// 1 % on a car), in the band the regression uses. It is reported once min_evidence_s of pairs
// have been seen and the peak's correlation exceeds min_correlation; until then the lag is 0
// (or fixed_lag_s when the config fixes it).
//
// Pure; not thread-safe; allocates only in the constructor.
#pragma once

#include <string>
#include <vector>

namespace vmass {

struct LagParams {
  bool enabled = true;
  double max_lag_s = 0.15;
  double memory_s = 120.0;  ///< of accepted pairs
  double min_correlation = 0.5;
  double min_evidence_s = 2.0;  ///< of accepted pairs
  double fixed_lag_s = -1.0;    ///< >= 0: use this lag instead of identifying it
  /// How far the best fit over the first pairs may be from the lag they identify, s: the
  /// provisional estimate (Pipeline, before the lag is identified) takes the held pairs at the
  /// best fit, and its interval what this much lag either way does to the mass. 0: no
  /// provisional estimate (the prior stays published until the lag is identified).
  double provisional_std_s = 0.03;

  std::string validate() const;
};

class LagEstimator {
 public:
  LagEstimator(const LagParams& params, double tick_rate_hz);

  /// Candidate lags 0 .. max_lag_ticks() (0 when disabled or fixed).
  int max_lag_ticks() const { return max_lag_; }
  /// One excited pair: its da and its y at every candidate lag (y_by_lag[0..max_lag_ticks()]).
  void add(double delta_accel_mps2, const double* y_by_lag);
  /// y at the identified lag (linear between ticks).
  double y_at_lag(const double* y_by_lag) const { return y_at(y_by_lag, lag_s_); }
  /// y at any lag in [0, max_lag_ticks()] ticks, s (linear between ticks).
  double y_at(const double* y_by_lag, double lag_s) const;
  /// Forget the evidence (a new vehicle).
  void reset();
  /// Another load: what the load before taught stays only as a prior worth min_evidence_s of
  /// pairs, so that the lag stays identified and the new load's pairs soon overrule it (pooled
  /// over two loads the fit misreads both). Without an identified lag, reset().
  void keep_as_prior();

  /// The lag in use, s (0 until identified; fixed_lag_s when fixed).
  double lag_s() const { return lag_s_; }
  bool identified() const { return identified_; }
  /// The lag the evidence so far points to, s: lag_s() once identified, else the best fit over
  /// the pairs seen (however few; 0 before any). For a provisional estimate, never for pairs
  /// that enter the belief.
  double best_lag_s() const;

 private:
  void update_estimate();
  /// The lag of the best fit, s, and its correlation.
  double peak_lag_s(double* correlation) const;

  LagParams params_;
  double rate_hz_;
  double forget_;
  int max_lag_;
  std::vector<double> s_ay_, s_yy_;
  double s_aa_ = 0.0;
  double evidence_s_ = 0.0;
  double lag_s_ = 0.0;
  bool identified_ = false;
};

}  // namespace vmass
