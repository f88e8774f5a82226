#include "suite_run.hpp"

#include <cmath>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "decoded_drive.hpp"
#include "result_json.hpp"
#include "vmass/baselines/baseline_factory.hpp"
#include "vmass/config/config.hpp"
#include "vmass/core/pipeline.hpp"
#include "vmass/sim/population.hpp"
#include "vmass/sim/population_drive.hpp"
#include "vmass/sim/population_scenarios.hpp"

namespace vmass::suite {

namespace {

bool is_vmass(const std::string& name) { return name == "rls" || name == "bayes"; }

// A per-tick series for plots: time, truth, estimate and interval.
class SeriesWriter {
 public:
  SeriesWriter(const std::string& path) {
    if (path.empty()) return;
    out_.open(path, std::ios::trunc);
    out_ << "time_s,true_mass_kg,mass_kg,ci_low_kg,ci_high_kg,converged\n";
  }
  void write(const scoring::EstimatePoint& p, double truth) {
    if (!out_.is_open() || count_++ % 10 != 0) return;  // 10 Hz is plenty for a plot
    out_ << to_seconds(p.time_us) << ',' << truth << ',';
    if (p.has_mass) out_ << p.mass_kg;
    out_ << ',';
    if (p.has_mass && p.has_interval)
      out_ << p.ci_low_kg << ',' << p.ci_high_kg;
    else
      out_ << ',';
    out_ << ',' << (p.converged ? 1 : 0) << '\n';
  }

 private:
  std::ofstream out_;
  long count_ = 0;
};

EstimatorResult run_vmass(const std::string& name, const Config& config,
                          const std::vector<Sample>& samples, const Truth& truth,
                          const std::string& series_path) {
  PipelineParams params = config.pipeline;
  params.estimator.type = name == "rls" ? RegressorType::kRls : RegressorType::kBayes;
  auto pipeline = std::make_unique<Pipeline>(params);
  return run_pipeline(name, *pipeline, samples, truth, series_path);
}

EstimatorResult run_baseline(const std::string& name, const Config& config,
                             const std::vector<Sample>& samples, const Truth& truth,
                             const std::string& series_path) {
  EstimatorResult r;
  r.estimator = name;
  const VehicleParams& v = config.pipeline.vehicle;
  baselines::NominalVehicle nominal;
  nominal.empty_mass_kg = v.empty_mass_kg;
  nominal.wheel_radius_m = v.wheel_radius_m;
  nominal.brake_gain_n_per_pa = v.brake_gain_n_per_pa;
  nominal.rotating_mass_kg = v.rotating_mass_kg;
  nominal.drag_area_m2 = v.drag_area_m2;
  nominal.air_density_kg_per_m3 = v.air_density_kg_per_m3;
  nominal.rolling_resistance_coeff = v.rolling_resistance_coeff;
  nominal.gravity_mps2 = v.gravity_mps2;
  auto baseline =
      baselines::make_baseline(name, nominal, config.pipeline.estimator.differencing.tick_rate_hz);
  if (!baseline) {
    r.supported = false;
    r.unsupported_reason = "unknown estimator '" + name + "'";
    return r;
  }
  scoring::AccuracyMetrics metrics(truth);
  SeriesWriter series(series_path);
  for (const Sample& s : samples) {
    baseline->step(s);
    const baselines::BaselineEstimate e = baseline->estimate();
    scoring::EstimatePoint p{s.time_us,   e.has_mass,   e.mass_kg, e.has_interval,
                             e.ci_low_kg, e.ci_high_kg, false};
    metrics.add(p);
    series.write(p, truth.mass_at(p.time_us));
  }
  r.accuracy = metrics.result();
  const double ticks = static_cast<double>(std::max<std::size_t>(1, samples.size()));
  r.availability_longitudinal = static_cast<double>(baseline->estimate().updates) / ticks;
  r.pairs_used = baseline->estimate().updates;
  return r;
}

std::string series_path(const RunSpec& spec, const std::string& estimator, sim::Knowledge k) {
  if (spec.series_dir.empty()) return "";
  return spec.series_dir + "/" + spec.vehicle_id + "_" + spec.scenario + "_s" +
         std::to_string(spec.seed) + "_" + std::string(sim::knowledge_name(k)) + "_" + estimator +
         ".csv";
}

// Seconds of |dv/dt| > 0.3 m/s^2 above 2 m/s in the truth (the "excited" drive time).
double excited_seconds(const sim::SimulationResult& result) {
  int ticks = 0;
  for (const sim::TruthRow& t : result.truth) {
    if (t.speed_mps > 2.0 && std::abs(t.long_accel_mps2) > 0.3) ++ticks;
  }
  return ticks / result.tick_rate_hz;
}

}  // namespace

Truth truth_track(const sim::SimulationResult& r, TimeUs time_offset_us) {
  std::vector<TimeUs> times;
  std::vector<double> masses, speeds;
  for (const sim::TruthRow& row : r.truth) {
    times.push_back(row.time_us + time_offset_us);
    masses.push_back(row.mass_kg);
    speeds.push_back(row.speed_mps);
  }
  return Truth(std::move(times), std::move(masses), std::move(speeds));
}

EstimatorResult run_pipeline(const std::string& name, Pipeline& pipeline,
                             const std::vector<Sample>& samples, const Truth& truth,
                             const std::string& series_path) {
  EstimatorResult r;
  r.estimator = name;
  scoring::AccuracyMetrics metrics(truth);
  SeriesWriter series(series_path);
  for (const Sample& s : samples) {
    r.verdicts.add(pipeline.step(s).events);
    const Estimate& e = pipeline.estimate();
    scoring::EstimatePoint p{e.time_us,
                             e.has_mass(),
                             e.mass_kg,
                             e.has_mass(),
                             e.ci_low_kg,
                             e.ci_high_kg,
                             e.status == EstimateStatus::kConverged};
    metrics.add(p);
    series.write(p, truth.mass_at(p.time_us));
  }
  const Estimate& e = pipeline.estimate();
  r.accuracy = metrics.result();
  const double ticks = static_cast<double>(std::max(1L, e.blocks[0].ticks));
  r.accepted_longitudinal = e.blocks[0].accepted;
  r.accepted_lateral = e.blocks[1].accepted;
  r.availability_longitudinal = static_cast<double>(e.blocks[0].accepted) / ticks;
  r.availability_lateral = static_cast<double>(e.blocks[1].accepted) /
                           static_cast<double>(std::max(1L, e.blocks[1].ticks));
  r.pairs_used = e.pairs_used;
  r.status_end = std::string(status_name(e.status));
  r.reason_end = std::string(reason_name(e.reason));
  r.initial_mass_kg = e.initial_mass_kg;
  r.identified_lag_s = pipeline.longitudinal().lag().lag_s();
  r.accel_noise_mps2 = pipeline.longitudinal().accel_noise_mps2();
  r.rotating_accel =
      pipeline.longitudinal().rotating_from_wheel_speed() ? "wheel_speed" : "accelerometer";
  const double refresh_s = pipeline.longitudinal().speed_refresh().mean_interval_s();
  if (std::isfinite(refresh_s)) r.speed_refresh_s = refresh_s;
  if (const std::optional<PairTermFit> fit = pipeline.pair_term_fit()) {
    r.rotating_error = fit->rotating_error;
    r.rotating_error_std = fit->rotating_error_std;
    r.pair_term_shift_kg = fit->mass_shift_kg;
  }
  return r;
}

std::vector<std::string> default_estimators() {
  std::vector<std::string> out = {"rls", "bayes"};
  for (const std::string& b : baselines::baseline_names()) out.push_back(b);
  return out;
}

RunResult run_suite_case(const RunSpec& spec, const std::string& work_dir) {
  RunResult out;
  out.spec = spec;
  sim::DrawnVehicle vehicle;
  if (!sim::parse_vehicle_id(spec.vehicle_id, &vehicle, &out.error)) return out;
  sim::apply_torque_signal_variant(spec.torque_signal, &vehicle);
  out.vehicle_class = std::string(sim::vehicle_class_name(vehicle.vehicle_class));
  sim::PopulationRun run;
  if (auto m = sim::make_population_run(vehicle, spec.scenario, spec.seed, spec.realism, &run);
      !m.empty()) {
    out.error = m;
    return out;
  }
  sim::SimulationResult result;  // one drive, handed to a team per kind of knowledge
  if (auto m = sim::simulate(run.physics, run.simulation, &result); !m.empty()) {
    out.error = m;
    return out;
  }
  out.duration_s = run.physics.duration_s;
  out.initial_true_mass_kg = result.truth.front().mass_kg;
  out.excited_s = excited_seconds(result);
  if (spec.realism.has(sim::Effect::kDatasheetErrors)) {
    out.true_rotating_error = 1.0 / (1.0 + vehicle.errors.rotating_mass) - 1.0;
  }
  const Truth truth = truth_track(result, 0);
  for (sim::Knowledge k : spec.knowledge) {
    DecodeOptions decode_options;
    decode_options.estimator_yaml = spec.estimator_yaml;
    DecodedDrive d =
        decode_drive(*sim::population_team(vehicle, run, k), result, decode_options, work_dir);
    d.error = without_dir(d.error, work_dir);
    for (const std::string& name : spec.estimators) {
      if (!d.config) {
        EstimatorResult r;
        r.estimator = name;
        r.knowledge = k;
        r.supported = false;
        r.unsupported_reason = d.error;
        out.results.push_back(r);
        continue;
      }
      const std::string series = series_path(spec, name, k);
      EstimatorResult r = is_vmass(name) ? run_vmass(name, *d.config, d.samples, truth, series)
                                         : run_baseline(name, *d.config, d.samples, truth, series);
      r.knowledge = k;
      out.results.push_back(r);
    }
  }
  return out;
}

std::string to_json_lines(const RunResult& run) {
  std::string out;
  nlohmann::json base;
  base["vehicle"] = run.spec.vehicle_id;
  base["class"] = run.vehicle_class;
  base["scenario"] = run.spec.scenario;
  base["seed"] = run.spec.seed;
  base["realism"] = run.spec.realism_label;
  base["duration_s"] = run.duration_s;
  base["initial_true_mass_kg"] = run.initial_true_mass_kg;
  base["excited_s"] = run.excited_s;
  base["true_rotating_error"] = run.true_rotating_error;
  if (run.spec.torque_signal != sim::TorqueSignalVariant::kAsDrawn) {
    base["torque_signal"] = std::string(sim::torque_signal_variant_name(run.spec.torque_signal));
  }
  if (!run.error.empty()) {
    nlohmann::json j = base;
    j["error"] = run.error;
    return j.dump() + "\n";
  }
  for (const EstimatorResult& r : run.results) {
    nlohmann::json j = base;
    add_result_fields(r, &j);
    out += j.dump() + "\n";
  }
  return out;
}

}  // namespace vmass::suite
