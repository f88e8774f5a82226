#include "suite_run.hpp"

#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "vmass/baselines/baseline_factory.hpp"
#include "vmass/can/candump.hpp"
#include "vmass/config/config.hpp"
#include "vmass/core/pipeline.hpp"
#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/candump_frame_source.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/signals/signal_mapping.hpp"
#include "vmass/signals/signal_table.hpp"
#include "vmass/sim/population.hpp"
#include "vmass/sim/population_scenarios.hpp"
#include "vmass/sim/population_writer.hpp"
#include "vmass/sim/vehicle_bus.hpp"

namespace vmass::suite {

namespace {

bool is_vmass(const std::string& name) { return name == "rls" || name == "bayes"; }

TruthTrack truth_track(const sim::SimulationResult& r) {
  TruthTrack t;
  for (const sim::TruthRow& row : r.truth) {
    t.time_us.push_back(row.time_us);
    t.mass_kg.push_back(row.mass_kg);
    t.speed_mps.push_back(row.speed_mps);
  }
  return t;
}

std::string write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  return out ? "" : "cannot write " + path;
}

// A per-tick series for plots: time, truth, estimate and interval.
class SeriesWriter {
 public:
  SeriesWriter(const std::string& path) {
    if (path.empty()) return;
    out_.open(path, std::ios::trunc);
    out_ << "time_s,true_mass_kg,mass_kg,ci_low_kg,ci_high_kg\n";
  }
  void write(const EstimatePoint& p, double truth) {
    if (!out_.is_open() || count_++ % 10 != 0) return;  // 10 Hz is plenty for a plot
    out_ << to_seconds(p.time_us) << ',' << truth << ',';
    if (p.has_mass) out_ << p.mass_kg;
    out_ << ',';
    if (p.has_mass && p.has_interval)
      out_ << p.ci_low_kg << ',' << p.ci_high_kg;
    else
      out_ << ',';
    out_ << '\n';
  }

 private:
  std::ofstream out_;
  long count_ = 0;
};

// The decoded ticks of one knowledge's bus, and its config.
struct Decoded {
  std::string error;  ///< the config or the mapping was refused (unsupported)
  std::optional<Config> config;
  std::vector<Sample> samples;
};

// Messages name the work directory's files; the report shows them by their own names.
std::string without_dir(std::string message, const std::string& dir) {
  const std::string prefix = dir + "/";
  for (std::size_t at = message.find(prefix); at != std::string::npos; at = message.find(prefix)) {
    message.erase(at, prefix.size());
  }
  return message;
}

Decoded decode(const sim::DrawnVehicle& vehicle, const sim::PopulationRun& run,
               const sim::SimulationResult& result, sim::Knowledge knowledge, const RunSpec& spec,
               const std::string& work_dir) {
  Decoded out;
  const sim::VehicleBus bus(vehicle);
  sim::BusOptions options = run.bus;
  options.torque_report_scale *= sim::torque_report_scale(vehicle, knowledge);
  std::vector<can::CanFrame> frames;
  if (auto m = bus.encode(result, options, &frames); !m.empty()) {
    out.error = "bus: " + m;
    return out;
  }
  std::string yaml = sim::datasheet_config_yaml(vehicle, run.realism, knowledge, "vehicle.dbc");
  if (!spec.estimator_yaml.empty()) yaml += "\n" + spec.estimator_yaml + "\n";
  const std::string config_path = work_dir + "/config.yaml";
  if (auto m = write_file(work_dir + "/vehicle.dbc", bus.dbc_text()); !m.empty()) {
    out.error = m;
    return out;
  }
  if (auto m = write_file(config_path, yaml); !m.empty()) {
    out.error = m;
    return out;
  }
  ConfigLoad loaded = load_config(config_path);
  if (!loaded.ok()) {
    out.error = loaded.error;
    return out;
  }
  signals::CanInputsLoad can = signals::load_can_inputs(*loaded.config);
  if (!can.ok()) {
    out.error = can.error;
    return out;
  }
  runtime::CanInputSource source(
      runtime::CandumpFrameSource::from_text(sim::candump_text(frames), "drive.log"),
      can.inputs->decoder, can.inputs->mapping);
  out.samples.reserve(result.truth.size() + 16);
  runtime::UnpacedClock clock;
  runtime::TickDriver(source, loaded.config->pipeline.estimator.differencing.tick_rate_hz)
      .run(clock, [&](std::int64_t, TimeUs t) { out.samples.push_back(source.sample_at(t)); });
  out.config = std::move(loaded.config);
  return out;
}

EstimatorResult run_vmass(const std::string& name, const Config& config,
                          const std::vector<Sample>& samples, const TruthTrack& truth,
                          const std::string& series_path) {
  EstimatorResult r;
  r.estimator = name;
  PipelineParams params = config.pipeline;
  params.estimator.type = name == "rls" ? RegressorType::kRls : RegressorType::kBayes;
  auto pipeline = std::make_unique<Pipeline>(params);
  AccuracyMetrics metrics(truth);
  SeriesWriter series(series_path);
  for (const Sample& s : samples) {
    pipeline->step(s);
    const Estimate& e = pipeline->estimate();
    EstimatePoint p{e.time_us,
                    e.has_mass(),
                    e.mass_kg,
                    e.has_mass(),
                    e.ci_low_kg,
                    e.ci_high_kg,
                    e.status == EstimateStatus::kConverged};
    metrics.add(p);
    series.write(p, truth.mass_at(p.time_us));
  }
  const Estimate& e = pipeline->estimate();
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
  r.identified_lag_s = pipeline->longitudinal().lag().lag_s();
  r.accel_noise_mps2 = pipeline->longitudinal().accel_noise_mps2();
  return r;
}

EstimatorResult run_baseline(const std::string& name, const Config& config,
                             const std::vector<Sample>& samples, const TruthTrack& truth,
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
  AccuracyMetrics metrics(truth);
  SeriesWriter series(series_path);
  for (const Sample& s : samples) {
    baseline->step(s);
    const baselines::BaselineEstimate e = baseline->estimate();
    EstimatePoint p{s.time_us,   e.has_mass,   e.mass_kg, e.has_interval,
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

}  // namespace

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
  out.vehicle_class = std::string(sim::vehicle_class_name(vehicle.vehicle_class));
  sim::PopulationRun run;
  if (auto m = sim::make_population_run(vehicle, spec.scenario, spec.seed, spec.realism, &run);
      !m.empty()) {
    out.error = m;
    return out;
  }
  sim::SimulationOptions options;
  options.seed = spec.seed;
  options.realism = spec.realism;
  options.record_ecu_trace = true;
  sim::SimulationResult result;
  if (auto m = sim::simulate(run.physics, options, &result); !m.empty()) {
    out.error = m;
    return out;
  }
  out.duration_s = run.physics.duration_s;
  out.initial_true_mass_kg = result.truth.front().mass_kg;
  const TruthTrack truth = truth_track(result);
  for (sim::Knowledge k : spec.knowledge) {
    Decoded d = decode(vehicle, run, result, k, spec, work_dir);
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

namespace {

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

}  // namespace

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
  if (!run.error.empty()) {
    nlohmann::json j = base;
    j["error"] = run.error;
    return j.dump() + "\n";
  }
  for (const EstimatorResult& r : run.results) {
    nlohmann::json j = base;
    const AccuracyResult& a = r.accuracy;
    j["knowledge"] = std::string(sim::knowledge_name(r.knowledge));
    j["estimator"] = r.estimator;
    j["supported"] = r.supported;
    if (!r.supported) {
      j["unsupported_reason"] = r.unsupported_reason;
      out += j.dump() + "\n";
      continue;
    }
    j["has_estimate"] = a.has_estimate;
    j["final_mass_kg"] = number(a.final_mass_kg);
    j["true_final_mass_kg"] = number(a.true_final_mass_kg);
    j["final_error_pct"] = number(a.final_error_pct);
    j["error_20s_pct"] = number(a.error_at_pct[0]);
    j["error_60s_pct"] = number(a.error_at_pct[1]);
    j["time_within_5_s"] = number(a.time_within_s[0]);
    j["time_within_2_s"] = number(a.time_within_s[1]);
    j["time_within_1_s"] = number(a.time_within_s[2]);
    j["rms_last_half_pct"] = number(a.rms_last_half_pct);
    j["covered_20s"] = a.covered_at[0];
    j["covered_60s"] = a.covered_at[1];
    j["covered_end"] = a.covered_end;
    j["halfwidth_end_pct"] = number(a.halfwidth_end_pct);
    j["converged_outside_fraction"] = number(a.converged_outside_fraction);
    j["availability_longitudinal"] = number(r.availability_longitudinal);
    j["availability_lateral"] = number(r.availability_lateral);
    j["accepted_longitudinal"] = r.accepted_longitudinal;
    j["accepted_lateral"] = r.accepted_lateral;
    j["pairs_used"] = r.pairs_used;
    j["status_end"] = r.status_end;
    j["reason_end"] = r.reason_end;
    j["initial_mass_kg"] = number(r.initial_mass_kg);
    j["identified_lag_s"] = number(r.identified_lag_s);
    j["accel_noise_mps2"] = number(r.accel_noise_mps2);
    out += j.dump() + "\n";
  }
  return out;
}

}  // namespace vmass::suite
