#include "vmass/calibrate/calibration_report.hpp"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "vmass/config/suspension_section.hpp"
#include "vmass/config/yaml_reader.hpp"
#include "vmass/core/static_initializer.hpp"
#include "vmass/json/json.hpp"

namespace vmass::calibrate {
namespace {

// Locale-free (snprintf with the "C" numeric locale the tools keep) number for YAML/JSON/text.
std::string num(double v, const char* format = "%.10g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// 10 significant digits, as the text report's numbers were.
json::Json json_num(double v) { return json::significant(v, 10); }

/// What Ceres's termination word means for a reader who does not know Ceres.
std::string termination_meaning(const std::string& word) {
  if (word == "CONVERGENCE") return "converged: the fit stopped changing within Ceres's tolerances";
  if (word == "NO_CONVERGENCE") {
    return "not converged: the iteration limit came first, the fit may be off";
  }
  if (word == "FAILURE") return "failed: the solver could not make progress";
  if (word == "USER_SUCCESS" || word == "USER_FAILURE") return "stopped by vmass-calibrate";
  return word.empty() ? std::string("not run") : word;
}

std::string fixed(double v, int decimals, int width = 0) {
  if (!std::isfinite(v)) {
    std::string s = std::isnan(v) ? "-" : (v > 0 ? "inf" : "-inf");
    return std::string(static_cast<std::size_t>(std::max(0, width - static_cast<int>(s.size()))),
                       ' ') +
           s;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%*.*f", width, decimals, v);
  return buf;
}

// "value unit  std s  95% [lo, hi]" with a scale applied.
std::string estimate_text(const Estimate& e, double scale, int decimals, const std::string& unit,
                          double confidence) {
  std::string s = fixed(e.value * scale, decimals) + " " + unit;
  if (std::isfinite(e.std)) {
    s += "   std " + fixed(e.std * scale, decimals) + "   " + num(100.0 * confidence, "%g") +
         "% [" + fixed(e.low * scale, decimals) + ", " + fixed(e.high * scale, decimals) + "]";
  } else {
    s += "   std not estimable";
  }
  return s;
}

void json_estimate(json::Json* out, const std::string& key, const Estimate& e, double scale,
                   const std::string& unit_suffix) {
  (*out)[key + unit_suffix] = json_num(e.value * scale);
  (*out)[key + "_std" + unit_suffix] = json_num(e.std * scale);
  (*out)[key + "_ci_low" + unit_suffix] = json_num(e.low * scale);
  (*out)[key + "_ci_high" + unit_suffix] = json_num(e.high * scale);
}

void json_stats(json::Json* out, const FitStats& s) {
  (*out)["steps_used"] = s.steps_used;
  (*out)["robust_scale_mm"] = json_num(s.robust_scale_mm);
  (*out)["residual_std_mm"] = json_num(s.residual_std_mm);
  (*out)["step_se_mm"] = json_num(s.step_se_mm);
  (*out)["effective_dof"] = json_num(s.effective_dof);
  (*out)["cost"] = json_num(s.cost);
  (*out)["iterations"] = s.iterations;
  (*out)["termination"] = s.termination;
  (*out)["termination_meaning"] = termination_meaning(s.termination);
}

/// How the report names a covariance parameter, and its SI unit.
struct ParameterName {
  const char* key;
  const char* words;
  const char* unit;
};

constexpr ParameterName kParameterNames[] = {{"stiffness_n_per_m", "stiffness", "N/m"},
                                             {"zero_offset_m", "zero offset", "m"},
                                             {"knee_m", "knee", "m"},
                                             {"rate_n_per_m2", "rate", "N/m^2"}};

ParameterName parameter_name(const std::string& key) {
  for (const ParameterName& p : kParameterNames) {
    if (key == p.key) return p;
  }
  return {key.c_str(), key.c_str(), "SI"};
}

/// The loads of the steps: the lightest and the heaviest at or below the knee (in the linear
/// fit), the lightest beyond it (NaN when none).
struct KneeSteps {
  double lightest_kg = std::numeric_limits<double>::quiet_NaN();
  double last_below_kg = std::numeric_limits<double>::quiet_NaN();
  double first_beyond_kg = std::numeric_limits<double>::quiet_NaN();
};

KneeSteps knee_steps(const SuspensionCalibration& cal) {
  KneeSteps k;
  for (const BallastStepFit& s : cal.steps) {
    const double m = s.step.added_mass_kg;
    if (s.in_linear_fit) {
      if (!(m <= k.last_below_kg)) k.last_below_kg = m;
      if (!(m >= k.lightest_kg)) k.lightest_kg = m;
    } else if (!(m >= k.first_beyond_kg)) {
      k.first_beyond_kg = m;
    }
  }
  return k;
}

/// What would separate two parameters that trade off, from the steps the fit had. Measured on
/// synthetic tests of the progressive curve (0.02 mm noise): stiffness and knee (and the other
/// pairs with the knee or rate) fall from r = 0.90 to 0.29 when the gap between the last step
/// below the knee and the first beyond it is filled, and rise with more steps beyond it; knee and
/// rate stay at 0.89-0.97 whatever the steps (0.84 with one step at 2.5 times the load), the
/// shape of the model; stiffness and zero offset fall from 0.96 to 0.81 with a step at zero.
std::string trade_off_advice(const std::string& a, const std::string& b,
                             const SuspensionCalibration& cal) {
  const KneeSteps k = knee_steps(cal);
  auto involves = [&](const char* key) { return a == key || b == key; };
  if (involves("knee_m") && involves("rate_n_per_m2")) {
    return "a later knee with a steeper rate bends the curve alike; more steps reduce this only "
           "a little (heavier ones beyond the knee most): judge the written curve by its "
           "per-step residuals and the mass check, not these two alone";
  }
  if (involves("knee_m") || involves("rate_n_per_m2")) {
    return "more ballast steps between " + num(k.last_below_kg, "%g") + " and " +
           num(k.first_beyond_kg, "%g") +
           " kg, where the linear part ends and the knee lies, would separate them";
  }
  if (involves("stiffness_n_per_m") && involves("zero_offset_m")) {
    if (k.lightest_kg > 0.0) {
      return "a step at zero added load (the lightest is " + num(k.lightest_kg, "%g") +
             " kg) would separate them";
    }
    return "steps spread evenly from zero added load to " + num(k.last_below_kg, "%g") +
           " kg would separate them (to about r = 0.8, no further)";
  }
  return "more ballast steps would separate them";
}

/// A strongly correlated pair with what would separate it.
struct TradeOff {
  CorrelatedPair pair;
  std::string advice;
};

std::vector<TradeOff> trade_offs(const ParameterCovariance& c, const SuspensionCalibration& cal) {
  std::vector<TradeOff> out;
  for (const CorrelatedPair& p : strongly_correlated(c)) {
    out.push_back({p, trade_off_advice(c.names[p.first], c.names[p.second], cal)});
  }
  return out;
}

/// "stiffness and knee trade off (r = -0.97): advice".
std::string trade_off_text(const ParameterCovariance& c, const TradeOff& t) {
  return std::string(parameter_name(c.names[t.pair.first]).words) + " and " +
         parameter_name(c.names[t.pair.second]).words +
         " trade off (r = " + num(t.pair.correlation, "%.2f") + "): " + t.advice;
}

/// One matrix of the covariance: a header of parameter names, a row per parameter.
std::string matrix_text(const ParameterCovariance& c, bool correlation) {
  const std::size_t n = c.size();
  constexpr std::size_t kLabel = 20;
  std::string o = correlation ? "  correlation" : "  covariance (SI)";
  o += std::string(kLabel - o.size(), ' ');
  for (std::size_t j = 0; j < n; ++j) {
    const std::string w = parameter_name(c.names[j]).words;
    o += std::string(w.size() < 13 ? 13 - w.size() : 1, ' ') + w;
  }
  o += "\n";
  for (std::size_t i = 0; i < n; ++i) {
    const ParameterName p = parameter_name(c.names[i]);
    std::string label = "    " + std::string(p.words);
    if (!correlation) label += std::string(" [") + p.unit + "]";
    o += label + std::string(label.size() < kLabel ? kLabel - label.size() : 1, ' ');
    for (std::size_t j = 0; j < n; ++j) {
      o +=
          correlation ? fixed(c.correlation_at(i, j), 3, 13) : num(c.covariance_at(i, j), "%13.4e");
    }
    o += "\n";
  }
  return o;
}

/// The correlation and covariance of a model's parameters, and its trade-offs (or why not).
std::string covariance_text(const ParameterCovariance& c, const SuspensionCalibration& cal) {
  if (!c.estimable) return "  correlation     not estimable: " + c.reason + "\n";
  std::string o = matrix_text(c, true) + matrix_text(c, false);
  o += "    (entry i, j in unit_i x unit_j; sqrt of the diagonal is each std)\n";
  const std::vector<TradeOff> pairs = trade_offs(c, cal);
  if (pairs.empty()) o += "  trade-offs      none (every |r| <= 0.9)\n";
  for (const TradeOff& t : pairs) o += "  trade-off       " + trade_off_text(c, t) + "\n";
  return o;
}

/// parameters, covariance_estimable, covariance_reason, correlation, covariance, trade_offs.
void json_covariance(json::Json* out, const ParameterCovariance& c,
                     const SuspensionCalibration& cal) {
  (*out)["parameters"] = c.names;
  (*out)["covariance_estimable"] = c.estimable;
  (*out)["covariance_reason"] = c.reason;
  json::Json correlation = nullptr, covariance = nullptr;
  if (c.estimable) {
    for (std::size_t i = 0; i < c.size(); ++i) {
      for (std::size_t j = 0; j < c.size(); ++j) {
        correlation[c.names[i]][c.names[j]] = json_num(c.correlation_at(i, j));
        covariance[c.names[i]][c.names[j]] = json_num(c.covariance_at(i, j));
      }
    }
  }
  (*out)["correlation"] = correlation;
  (*out)["covariance"] = covariance;
  (*out)["trade_offs"] = json::Json::array();
  for (const TradeOff& t : trade_offs(c, cal)) {
    (*out)["trade_offs"].push_back({{"parameters", {c.names[t.pair.first], c.names[t.pair.second]}},
                                    {"correlation", json_num(t.pair.correlation)},
                                    {"text", trade_off_text(c, t)},
                                    {"advice", t.advice}});
  }
}

json::Json progressive_json(const ProgressiveFit& pr, const SuspensionCalibration& cal) {
  json::Json j;
  j["detected"] = pr.detected;
  j["reason"] = pr.reason;
  json_estimate(&j, "stiffness", pr.stiffness_n_per_m, 1.0, "_n_per_m");
  json_estimate(&j, "zero_offset", pr.zero_offset_m, 1e3, "_mm");
  json_estimate(&j, "knee", pr.knee_m, 1e3, "_mm");
  json_estimate(&j, "rate", pr.rate_n_per_m2, 1.0, "_n_per_m2");
  j["f_statistic"] = json_num(pr.f_statistic);
  j["f_critical"] = json_num(pr.f_critical);
  json_stats(&j, pr.stats);
  json_covariance(&j, pr.covariance, cal);
  return j;
}

json::Json geometry_json(const LoadGeometry& g) {
  return {{"wheelbase_m", json_num(g.wheelbase_m)},
          {"cg_to_front_axle_m", json_num(g.cg_to_front_axle_m)},
          {"gravity_mps2", json_num(g.gravity_mps2)},
          {"wheel_force_per_kg_n", json_num(g.wheel_force_per_kg())}};
}

json::Json suspension_json(const SuspensionParams& p) {
  return {{"stiffness_n_per_m", json_num(p.stiffness_n_per_m)},
          {"empty_deflection_m", json_num(p.empty_deflection_m)},
          {"progressive_knee_m", json_num(p.progressive_knee_m)},
          {"progressive_rate_n_per_m2", json_num(p.progressive_rate_n_per_m2)},
          {"linear_range_kg", json_num(p.linear_range_kg)},
          {"calibrated_range_kg", json_num(p.calibrated_range_kg)}};
}

json::Json step_json(const BallastStepFit& s) {
  return {{"added_mass_kg", json_num(s.step.added_mass_kg)},
          {"force_n", json_num(s.force_n)},
          {"deflection_mm", json_num(s.step.deflection_m * 1e3)},
          {"deflection_std_mm", json_num(s.step.deflection_std_m * 1e3)},
          {"samples", s.step.sample_count},
          {"start_s", json_num(s.step.start_s)},
          {"end_s", json_num(s.step.end_s)},
          {"linear_residual_mm", json_num(s.linear_residual_m * 1e3)},
          {"progressive_residual_mm", json_num(s.progressive_residual_m * 1e3)},
          {"in_linear_fit", s.in_linear_fit},
          {"outlier", s.outlier},
          {"linear_mass_error", json_num(s.linear_mass_error)}};
}

json::Json mass_check_json(const MassCheckRow& r) {
  return {{"added_mass_kg", json_num(r.added_mass_kg)},
          {"true_mass_kg", json_num(r.true_mass_kg)},
          {"linear_mass_kg", json_num(r.linear_mass_kg)},
          {"linear_error", json_num(r.linear_error)},
          {"progressive_mass_kg", json_num(r.progressive_mass_kg)},
          {"progressive_error", json_num(r.progressive_error)},
          {"beyond_linear_range", r.beyond_linear_range}};
}

}  // namespace

std::vector<MassCheckRow> mass_check(const SuspensionCalibration& calibration,
                                     const VehicleParams& vehicle) {
  const StaticInitParams params;
  const StaticInitializer linear(vehicle, calibration.linear_suspension_params(), params);
  const StaticInitializer written(vehicle, calibration.suspension_params(), params);
  std::vector<MassCheckRow> rows;
  for (const BallastStepFit& s : calibration.steps) {
    MassCheckRow r;
    r.added_mass_kg = s.step.added_mass_kg;
    r.true_mass_kg = vehicle.empty_mass_kg + s.step.added_mass_kg;
    r.deflection_m = s.step.deflection_m;
    r.linear_mass_kg = linear.mass_from_deflection_kg(s.step.deflection_m);
    r.progressive_mass_kg = written.mass_from_deflection_kg(s.step.deflection_m);
    r.linear_error = (r.linear_mass_kg - r.true_mass_kg) / r.true_mass_kg;
    r.progressive_error = (r.progressive_mass_kg - r.true_mass_kg) / r.true_mass_kg;
    r.beyond_linear_range = s.step.added_mass_kg > calibration.linear_range_kg;
    rows.push_back(r);
  }
  return rows;
}

std::string suspension_yaml(const SuspensionCalibration& calibration,
                            const std::vector<std::string>& header_comment) {
  SuspensionParams p = calibration.suspension_params();
  const bool prog = calibration.progressive.detected;
  const Estimate& c =
      prog ? calibration.progressive.stiffness_n_per_m : calibration.linear.stiffness_n_per_m;
  const Estimate& z0 =
      prog ? calibration.progressive.zero_offset_m : calibration.linear.zero_offset_m;
  auto std_comment = [](const Estimate& e, double scale, const char* unit) {
    return std::isfinite(e.std) ? "std " + num(e.std * scale, "%.3g") + " " + unit : std::string();
  };
  const bool linear_range = p.linear_range_kg > 0.0;
  if (!linear_range) p.linear_range_kg = 1e-3;  // the loader wants > 0
  const FieldComments comments{
      {"stiffness_n_per_m", std_comment(c, 1.0, "N/m")},
      {"empty_deflection_m", std_comment(z0, 1.0, "m")},
      {"progressive_knee_m",
       prog ? std_comment(calibration.progressive.knee_m, 1.0, "m") : "no bump stop"},
      {"progressive_rate_n_per_m2",
       prog ? std_comment(calibration.progressive.rate_n_per_m2, 1.0, "N/m^2") : ""},
      {"linear_range_kg", linear_range ? "" : "no step within tolerance"}};
  std::string out;
  for (const std::string& line : header_comment) out += "# " + line + "\n";
  return out + suspension_section_yaml(p, comments);
}

std::string check_suspension_yaml(const std::string& yaml) {
  // Read back with the loader's own reader and field table, so that its bounds apply as they
  // are, not a copy of them that could drift.
  const std::string name = "snippet";
  try {
    const YAML::Node root = YAML::Load(yaml);
    YamlReader r(root["suspension"], name, "suspension");
    SuspensionParams p;
    read_suspension_section(r, /*present=*/true, &p);
    return p.validate();
  } catch (const ConfigError& e) {
    // "snippet:LINE: suspension.KEY: ...": the line of a text nobody sees says nothing.
    const std::string m = e.what();
    const std::size_t after_line = m.find(": ");
    return after_line == std::string::npos ? m : m.substr(after_line + 2);
  } catch (const YAML::Exception& e) {
    return std::string("not YAML: ") + e.what();
  }
}

std::string calibration_json(const SuspensionCalibration& cal,
                             const std::vector<MassCheckRow>& mass_rows) {
  const LinearFit& lin = cal.linear;
  json::Json j;
  json_estimate(&j, "stiffness", lin.stiffness_n_per_m, 1.0, "_n_per_m");
  json_estimate(&j, "zero_offset", lin.zero_offset_m, 1e3, "_mm");
  j["linear_range_kg"] = json_num(cal.linear_range_kg);
  j["calibrated_range_kg"] = json_num(cal.calibrated_range_kg);
  j["linear_tolerance"] = json_num(cal.linear_tolerance);
  json_stats(&j["linear"], lin.stats);
  json_covariance(&j["linear"], lin.covariance, cal);
  j["progressive"] = progressive_json(cal.progressive, cal);
  j["geometry"] = geometry_json(cal.geometry);
  j["suspension"] = suspension_json(cal.suspension_params());
  j["steps"] = json::Json::array();
  for (const BallastStepFit& s : cal.steps) j["steps"].push_back(step_json(s));
  j["mass_check"] = json::Json::array();
  for (const MassCheckRow& r : mass_rows) j["mass_check"].push_back(mass_check_json(r));
  j["warnings"] = cal.warnings;
  return json::dump(j);
}

std::string calibration_text(const SuspensionCalibration& cal,
                             const std::vector<MassCheckRow>& mass_rows) {
  const double conf = 0.95;
  const LinearFit& lin = cal.linear;
  const ProgressiveFit& pr = cal.progressive;
  std::string o;
  o += "rear-right suspension from " + std::to_string(cal.steps.size()) + " ballast steps (" +
       num(cal.steps.front().step.added_mass_kg, "%g") + " .. " +
       num(cal.steps.back().step.added_mass_kg, "%g") + " kg)\n";
  o += "mass to force     dF_rr = dM g l_f / (2 l) = " +
       fixed(cal.geometry.wheel_force_per_kg(), 4) + " N/kg  (l " +
       fixed(cal.geometry.wheelbase_m, 3) + " m, l_f " + fixed(cal.geometry.cg_to_front_axle_m, 3) +
       " m, g " + num(cal.geometry.gravity_mps2, "%g") + " m/s^2)\n\n";
  o += "linear model (eq. 3) z = z0 + dF / c, " + std::to_string(lin.stats.steps_used) +
       " steps at or below the knee\n";
  o += "  stiffness       " + estimate_text(lin.stiffness_n_per_m, 1.0, 1, "N/m", conf) + "\n";
  o += "  zero offset     " + estimate_text(lin.zero_offset_m, 1e3, 4, "mm", conf) + "\n";
  o += "  residual std    " + fixed(lin.stats.residual_std_mm, 4) + " mm, step mean s.e. " +
       fixed(lin.stats.step_se_mm, 4) + " mm (Cauchy scale " + fixed(lin.stats.robust_scale_mm, 4) +
       " mm, dof " + fixed(lin.stats.effective_dof, 1) + ")\n";
  o += "  solver          " + termination_meaning(lin.stats.termination) + " (Ceres " +
       lin.stats.termination + ", " + std::to_string(lin.stats.iterations) + " iterations)\n";
  o += covariance_text(lin.covariance, cal);
  o += "progressive model dF = c (z - z0) + k2 max(0, z - z_knee)^2: " +
       std::string(pr.detected ? "bump stop detected" : "no bump stop (" + pr.reason + ")") + "\n";
  if (std::isfinite(pr.stiffness_n_per_m.value)) {
    o += "  stiffness       " + estimate_text(pr.stiffness_n_per_m, 1.0, 1, "N/m", conf) + "\n";
    o += "  zero offset     " + estimate_text(pr.zero_offset_m, 1e3, 4, "mm", conf) + "\n";
    o += "  knee            " + estimate_text(pr.knee_m, 1e3, 3, "mm", conf) + "\n";
    o += "  rate            " + estimate_text(pr.rate_n_per_m2, 1e-6, 4, "N/mm^2", conf) + "\n";
    o += "  residual std    " + fixed(pr.stats.residual_std_mm, 4) + " mm, step mean s.e. " +
         fixed(pr.stats.step_se_mm, 4) + " mm (Cauchy scale " + fixed(pr.stats.robust_scale_mm, 4) +
         " mm, dof " + fixed(pr.stats.effective_dof, 1) + "); F " + fixed(pr.f_statistic, 1) +
         " vs critical " + fixed(pr.f_critical, 2) + "\n";
    o += "  solver          " + termination_meaning(pr.stats.termination) + " (Ceres " +
         pr.stats.termination + ", " + std::to_string(pr.stats.iterations) + " iterations)\n";
    o += covariance_text(pr.covariance, cal);
  }
  o += "linear range      " + num(cal.linear_range_kg, "%g") +
       " kg (largest load the linear model reproduces within " +
       num(100.0 * cal.linear_tolerance, "%g") + " %)\n";
  o += "calibrated range  " + num(cal.calibrated_range_kg, "%g") + " kg\n\n";

  o += "per step    added_kg   force_N  deflection_mm  samples  lin_res_mm  prog_res_mm  "
       "lin_load_err_%  notes\n";
  for (const BallastStepFit& s : cal.steps) {
    std::string notes;
    if (s.outlier) notes += "outlier ";
    if (!s.in_linear_fit) notes += "beyond-knee ";
    o += "          " + fixed(s.step.added_mass_kg, 1, 10) + fixed(s.force_n, 1, 10) +
         fixed(s.step.deflection_m * 1e3, 4, 15) + std::string(2, ' ') +
         fixed(s.step.sample_count, 0, 7) + fixed(s.linear_residual_m * 1e3, 4, 12) +
         fixed(s.progressive_residual_m * 1e3, 4, 13) +
         (s.step.added_mass_kg != 0.0 ? fixed(100.0 * s.linear_mass_error, 2, 16)
                                      : std::string(16 - 1, ' ') + "-") +
         "  " + notes + "\n";
  }
  if (!mass_rows.empty()) {
    o += "\nstatic initialisation, eq. (3) (StaticInitializer::mass_from_deflection_kg)\n";
    o += "   added_kg   true_kg   linear_kg  lin_err_%  progressive_kg  prog_err_%\n";
    for (const MassCheckRow& r : mass_rows) {
      o += fixed(r.added_mass_kg, 1, 11) + fixed(r.true_mass_kg, 1, 10) +
           fixed(r.linear_mass_kg, 1, 12) + fixed(100.0 * r.linear_error, 2, 11) +
           fixed(r.progressive_mass_kg, 1, 16) + fixed(100.0 * r.progressive_error, 2, 12) +
           (r.beyond_linear_range ? "  beyond linear range" : "") + "\n";
    }
  }
  if (!cal.warnings.empty()) {
    o += "\n";
    for (const std::string& w : cal.warnings) o += "warning: " + w + "\n";
  }
  return o;
}

}  // namespace vmass::calibrate
