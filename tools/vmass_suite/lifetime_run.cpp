#include "lifetime_run.hpp"

#include <filesystem>
#include <memory>

#include <nlohmann/json.hpp>

#include "decoded_drive.hpp"
#include "result_json.hpp"
#include "suite_run.hpp"
#include "vmass/core/pipeline.hpp"
#include "vmass/service/pipeline_state.hpp"
#include "vmass/service/state_store.hpp"
#include "vmass/sim/lifetime.hpp"
#include "vmass/sim/population_drive.hpp"
#include "vmass/sim/population_scenarios.hpp"
#include "vmass/sim/random_stream.hpp"
#include "vmass/sim/simulator.hpp"

namespace vmass::suite {

namespace {

/// One way of carrying the vehicle through its life: a knowledge, with or without the
/// deflection sensor, one estimator. Its state file lives from drive to drive.
struct Variant {
  sim::Knowledge knowledge;
  bool deflection;
  bool known_mass;  ///< declared at the start of spec.known_mass_drives
  std::string estimator;
  std::string state_path;
  std::string keep_dir;  ///< "": nothing kept
};

std::string variant_name(const LifetimeSpec& spec, const Variant& v) {
  return spec.vehicle_id + "_" + std::string(sim::knowledge_name(v.knowledge)) + "_" +
         (v.deflection ? "deflection" : "no_deflection") + (v.known_mass ? "_known_mass" : "") +
         "_" + v.estimator;
}

std::vector<Variant> variants(const LifetimeSpec& spec, const sim::DrawnVehicle& vehicle,
                              const std::string& work_dir) {
  std::vector<Variant> out;
  // A levelled (air) rear axle's ride height carries no load: such a car has no "with".
  const bool reads_load = vehicle.sensors.deflection && !vehicle.vehicle.rear_levelling;
  for (sim::Knowledge k : spec.knowledge) {
    for (bool deflection : {true, false}) {
      if (deflection && !reads_load) continue;
      for (bool known : {false, true}) {
        if (known && spec.known_mass_drives.empty()) continue;
        for (const std::string& estimator : spec.estimators) {
          Variant v{k, deflection, known, estimator, "", ""};
          const std::string name = variant_name(spec, v);
          v.state_path = work_dir + "/" + name + ".state";
          if (!spec.keep_dir.empty()) v.keep_dir = spec.keep_dir + "/" + name;
          out.push_back(v);
        }
      }
    }
  }
  return out;
}

PipelineParams params_for(const Config& config, const std::string& estimator) {
  PipelineParams params = config.pipeline;
  params.estimator.type = estimator == "rls" ? RegressorType::kRls : RegressorType::kBayes;
  return params;
}

/// The published std at the end (relative to the mass): all of it, and its model part.
struct EndStd {
  double mass = 0.0;
  double model = 0.0;
};

EndStd end_std(const Estimate& last) {
  const double mass = last.mass_kg > 0.0 ? last.mass_kg : 1.0;
  return EndStd{last.mass_std_kg / mass, last.mass_model_std_kg / mass};
}

void add_end_std(const EndStd& std, nlohmann::json* j) {
  (*j)["mass_std_end_pct"] = 100.0 * std.mass;
  (*j)["model_std_end_pct"] = 100.0 * std.model;
}

/// What the lifetime drive learnt (Pipeline::learnt_scale(), after the drive), and what its
/// last estimate's std was made of (relative to its mass): the interval's honesty, by part.
struct Learnt {
  double scale = 1.0;
  double scale_std = 0.0;
  long evidence = 0;
  long changes = 0;
  EndStd end_std;  ///< the published std, and its model part (the scale, the floor, ...)
  /// The launches and stops (TyreWatch): this drive's counts and the launches' mean log s (NaN:
  /// none), the largest step found at the drive's start (in its std), the tyre changes told.
  double tyre_drive_launches = 0.0;
  double tyre_drive_stops = 0.0;
  double tyre_drive_log_ratio = std::numeric_limits<double>::quiet_NaN();
  double tyre_best_sigma = 0.0;
  double tyre_launch_std = 0.0;  ///< one launch's std of log s, as the watch takes it
  long tyre_changes_detected = 0;
};

/// What the user tells vmass before a drive's first tick.
struct Declarations {
  double known_mass_kg = 0.0;  ///< > 0: this mass is declared (a weighbridge ticket)
  double known_std_kg = 0.0;
  bool tyres_changed = false;  ///< the workshop's `vmass-ctl tyres-changed`
};

/// The drive through a pipeline restored from the variant's state file, saved there after it
/// as vmassd saves it at its stop (the open batch flushed; nothing saved without a prior), with
/// the declarations made before its first tick.
EstimatorResult lifetime_drive(const Variant& v, const DecodedDrive& d, const Truth& truth,
                               const std::string& series, const Declarations& told, bool* restored,
                               Learnt* learnt, std::string* error) {
  auto pipeline = std::make_unique<Pipeline>(params_for(*d.config, v.estimator));
  const service::StateRestore restore = service::restore_pipeline_state(v.state_path, *pipeline);
  *restored = restore.restored;
  if (restore.refused) *error = restore.message;
  if (told.tyres_changed) pipeline->tyres_changed();
  if (told.known_mass_kg > 0.0 &&
      !pipeline->declare_known_mass(told.known_mass_kg, told.known_std_kg)) {
    *error = "known mass " + std::to_string(told.known_mass_kg) + " kg refused";
  }
  EstimatorResult r = run_pipeline(v.estimator, *pipeline, d.samples, truth, series);
  const LearntScale& scale = pipeline->learnt_scale();
  *learnt = Learnt{scale.scale(), scale.relative_std(), scale.state().evidence,
                   scale.state().changes, end_std(pipeline->estimate())};
  const TyreWatch& tyres = pipeline->tyre_watch();
  const LaunchSums& launches = tyres.state().drive.kind[0];
  learnt->tyre_drive_launches = launches.count;
  learnt->tyre_drive_stops = tyres.state().drive.kind[1].count;
  if (launches.count > 0.0) learnt->tyre_drive_log_ratio = launches.mean();
  learnt->tyre_best_sigma = tyres.last_verdict().best_sigma;
  learnt->tyre_launch_std = tyres.launch_std();
  learnt->tyre_changes_detected = tyres.state().changes;
  pipeline->flush();
  const TimeUs saved_time_us = d.samples.empty() ? 0 : d.samples.back().time_us;
  std::string save_error;
  const service::StateSave saved = service::save_pipeline_state(
      v.state_path, pipeline->snapshot(), saved_time_us, pipeline->params(), &save_error);
  if (saved == service::StateSave::kFailed) {
    *error = save_error;
    r.supported = false;
    r.unsupported_reason = *error;
  } else if (saved == service::StateSave::kNotBelievable && error->empty()) {
    *error = v.state_path + ": " + save_error;  // reported like a refused restore
  }
  return r;
}

/// What the lifetime drive learnt, into its JSON line.
void add_learnt_fields(const Learnt& learnt, nlohmann::json* j) {
  (*j)["learnt_scale"] = learnt.scale;
  (*j)["learnt_scale_std"] = learnt.scale_std;
  (*j)["learnt_evidence"] = learnt.evidence;
  (*j)["learnt_changes"] = learnt.changes;
  add_end_std(learnt.end_std, j);
  (*j)["tyre_drive_launches"] = learnt.tyre_drive_launches;
  (*j)["tyre_drive_stops"] = learnt.tyre_drive_stops;
  if (std::isfinite(learnt.tyre_drive_log_ratio)) {
    (*j)["tyre_drive_log_ratio"] = learnt.tyre_drive_log_ratio;
  }
  (*j)["tyre_best_sigma"] = learnt.tyre_best_sigma;
  (*j)["tyre_launch_std"] = learnt.tyre_launch_std;
  (*j)["tyre_changes_detected"] = learnt.tyre_changes_detected;
}

EstimatorResult fresh_drive(const Variant& v, const DecodedDrive& d, const Truth& truth,
                            const std::string& series, EndStd* std) {
  auto pipeline = std::make_unique<Pipeline>(params_for(*d.config, v.estimator));
  EstimatorResult r = run_pipeline(v.estimator, *pipeline, d.samples, truth, series);
  *std = end_std(pipeline->estimate());
  return r;
}

bool is_known_mass_drive(const LifetimeSpec& spec, const sim::DrawnVehicle& vehicle, int index) {
  const bool truck_list = vehicle.vehicle_class == sim::VehicleClass::kHeavyTruck &&
                          !spec.truck_known_mass_drives.empty();
  for (int i : truck_list ? spec.truck_known_mass_drives : spec.known_mass_drives) {
    if (i == index) return true;
  }
  return false;
}

/// The mass a known-mass drive declares: the truth as a weighbridge reads it, off by an error
/// drawn from the std the declaration states. A ticket that is always exact would teach the
/// learnt scale more than any real one can. Drawn per (vehicle, life, drive), the same for
/// every variant of that drive.
double ticket_mass_kg(const LifetimeSpec& spec, const sim::DrawnVehicle& vehicle, int index,
                      double true_mass_kg) {
  const std::uint64_t drive_id =
      static_cast<std::uint64_t>(spec.life) * 1024 + static_cast<std::uint64_t>(index);
  sim::RandomStream rng(vehicle.stream_seed(),
                        sim::hash_name("known_mass_ticket") ^ sim::splitmix64(drive_id));
  return true_mass_kg * (1.0 + spec.known_mass_std_fraction * rng.normal());
}

std::string series_path(const LifetimeSpec& spec, const Variant& v, int drive, const char* mode) {
  if (spec.series_dir.empty()) return "";
  return spec.series_dir + "/" + variant_name(spec, v) + "_life" + std::to_string(spec.life) +
         "_drive" + std::to_string(drive) + "_" + mode + ".csv";
}

std::string keep_files(const Variant& v, const sim::LifetimeDrive& drive, const DecodedDrive& d) {
  if (v.keep_dir.empty()) return "";
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(v.keep_dir, ec);
  const std::string n = std::to_string(drive.index);
  const std::string dir = fs::path(d.config_path).parent_path().string();
  fs::copy_file(d.config_path, v.keep_dir + "/config.yaml", fs::copy_options::overwrite_existing,
                ec);
  if (!ec) {
    fs::copy_file(dir + "/vehicle.dbc", v.keep_dir + "/vehicle.dbc",
                  fs::copy_options::overwrite_existing, ec);
  }
  if (!ec && fs::exists(v.state_path)) {
    fs::copy_file(v.state_path, v.keep_dir + "/state_after_drive_" + n,
                  fs::copy_options::overwrite_existing, ec);
  }
  if (ec) return v.keep_dir + ": " + ec.message();
  return write_file(v.keep_dir + "/drive_" + n + ".log", d.log_text);
}

nlohmann::json drive_json(const LifetimeSpec& spec, const sim::DrawnVehicle& vehicle,
                          const sim::LifetimeDrive& drive, const sim::PopulationRun& run,
                          const sim::SimulationResult& result, const Variant& v) {
  nlohmann::json j;
  j["vehicle"] = spec.vehicle_id;
  j["class"] = std::string(sim::vehicle_class_name(vehicle.vehicle_class));
  j["scenario"] = drive.scenario;
  j["seed"] = drive.seed;
  j["realism"] = spec.realism_label;
  j["duration_s"] = run.physics.duration_s;
  j["initial_true_mass_kg"] = result.truth.front().mass_kg;
  j["life"] = spec.life;
  j["drive"] = drive.index;
  j["load_change"] = drive.load_change;
  j["payload_change_kg"] = drive.payload_change_kg;
  j["car_change"] = drive.car_change;
  j["tyre_radius_factor"] = drive.tyre_radius_factor;
  j["trailer_drag_factor"] = drive.trailer_drag_factor;
  j["trailer_rolling_factor"] = drive.trailer_rolling_factor;
  j["deflection_sensor"] = v.deflection;
  if (!spec.known_mass_drives.empty()) j["known_mass"] = v.known_mass;
  return j;
}

/// The drive simulated on the vehicle as it is then (its tyres); "" or why not.
std::string simulate_drive(const sim::DrawnVehicle& vehicle, const sim::LifetimeDrive& drive,
                           sim::Realism realism, sim::PopulationRun* run,
                           sim::SimulationResult* result) {
  if (auto m = sim::make_population_run(vehicle, drive.scenario, drive.seed, realism, run,
                                        &drive.payload);
      !m.empty()) {
    return m;
  }
  // The config keeps its radius, drag area and rolling coefficient.
  sim::fit_tyres(drive.tyre_radius_factor, &run->physics.vehicle);
  sim::couple_trailer(drive.trailer_drag_factor, drive.trailer_rolling_factor,
                      &run->physics.vehicle);
  return sim::simulate(run->physics, run->simulation, result);
}

}  // namespace

LifetimeResult run_lifetime(const LifetimeSpec& spec, const std::string& work_dir) {
  LifetimeResult out;
  sim::DrawnVehicle vehicle;
  if (!sim::parse_vehicle_id(spec.vehicle_id, &vehicle, &out.error)) return out;
  const std::vector<Variant> all = variants(spec, vehicle, work_dir);
  for (const Variant& v : all) std::filesystem::remove(v.state_path);
  const std::vector<sim::LifetimeDrive> plan =
      spec.plan.empty() ? sim::plan_lifetime(vehicle, spec.drives, spec.life,
                                             spec.tyre_change_drive, spec.trailer_change_drive)
                        : spec.plan;
  for (const sim::LifetimeDrive& drive : plan) {
    sim::PopulationRun run;
    sim::SimulationResult result;
    if (auto m = simulate_drive(vehicle, drive, spec.realism, &run, &result); !m.empty()) {
      out.error = m;
      return out;
    }
    const TimeUs offset = from_seconds(sim::kLifetimeDriveSpacingS * (drive.index - 1));
    const Truth truth = truth_track(result, offset);
    for (const Variant& v : all) {
      sim::DrawnVehicle on_bus = vehicle;
      on_bus.sensors.deflection = v.deflection;
      DecodeOptions decode_options{spec.estimator_yaml, offset, !v.keep_dir.empty()};
      DecodedDrive d = decode_drive(*sim::population_team(on_bus, run, v.knowledge), result,
                                    decode_options, work_dir);
      nlohmann::json base = drive_json(spec, vehicle, drive, run, result, v);
      if (!d.config) {
        EstimatorResult r;
        r.estimator = v.estimator;
        r.knowledge = v.knowledge;
        r.supported = false;
        r.unsupported_reason = without_dir(d.error, work_dir);
        for (const char* mode : {"lifetime", "fresh"}) {
          nlohmann::json j = base;
          j["mode"] = mode;
          add_result_fields(r, &j);
          out.json_lines += j.dump() + "\n";
        }
        continue;
      }
      bool restored = false;
      std::string restore_error;
      const bool declares = v.known_mass && is_known_mass_drive(spec, vehicle, drive.index);
      const double ticket_kg =
          ticket_mass_kg(spec, vehicle, drive.index, result.truth.front().mass_kg);
      const Declarations told{declares ? ticket_kg : 0.0, spec.known_mass_std_fraction * ticket_kg,
                              spec.tyre_change_declared && drive.index == spec.tyre_change_drive};
      Learnt learnt;
      EstimatorResult life =
          lifetime_drive(v, d, truth, series_path(spec, v, drive.index, "lifetime"), told,
                         &restored, &learnt, &restore_error);
      life.knowledge = v.knowledge;
      if (auto m = keep_files(v, drive, d); !m.empty()) {
        out.error = m;
        return out;
      }
      nlohmann::json j = base;
      j["mode"] = "lifetime";
      j["restored"] = restored;
      if (!restore_error.empty()) j["restore_message"] = without_dir(restore_error, work_dir);
      add_result_fields(life, &j);
      j["known_mass_declared"] = declares;
      if (declares) j["known_mass_declared_kg"] = told.known_mass_kg;
      j["tyres_declared"] = told.tyres_changed;
      add_learnt_fields(learnt, &j);
      out.json_lines += j.dump() + "\n";
      if (v.known_mass) continue;  // its fresh drives are the variant's without
      EndStd fresh_std;
      EstimatorResult fresh =
          fresh_drive(v, d, truth, series_path(spec, v, drive.index, "fresh"), &fresh_std);
      fresh.knowledge = v.knowledge;
      j = base;
      j["mode"] = "fresh";
      add_result_fields(fresh, &j);
      add_end_std(fresh_std, &j);
      out.json_lines += j.dump() + "\n";
    }
  }
  return out;
}

}  // namespace vmass::suite
