// vmass-suite: the accuracy suite. Runs population vehicles x scenarios x seeds, each under
// both kinds of knowledge, with vmass's estimators on their defaults and the baselines, and
// writes one JSON line per (run, knowledge, estimator) for tools/vmass_suite/accuracy_report.py.
//
//   vmass-suite [--population cars|trucks] [--vehicles N] [--first-seed S | --held-out]
//               [--seeds K] [--scenarios A,B]
//               [--estimators rls,bayes,...] [--knowledge known_scale,datasheet_scale]
//               [--realism all|none|...] [--estimator-yaml FILE] [--jobs J] --out FILE.jsonl
//               [--torque-signal as_drawn|engine_gear_index|engine_speed_ratio]
//   vmass-suite --ablation VEHICLE|auto [--scenarios ...] [--seeds K] --out FILE.jsonl
//   vmass-suite --runs VEHICLE:SCENARIO:SEED,... [--series-dir DIR] --out FILE.jsonl
//   vmass-suite --lifetime DRIVES [--vehicles N | --vehicle-ids ID,...] [--held-out] [--lives K]
//               [--known-mass-drives LIST [--truck-known-mass-drives LIST]]
//               [--tyre-change-drive K [--tyre-change-declared]]
//               [--trailer-change-drive L]
//               [--knowledge ...] [--estimators bayes,rls] [--keep-dir DIR] [--series-dir DIR]
//               [--jobs J] --out FILE.jsonl
//   vmass-suite --list-scenarios | --population-hash
//
// --lifetime drives each vehicle DRIVES drives in a row through the daemon's state file (loads
// changed while parked), beside the same drives fresh (lifetime_run.hpp); K lives per vehicle;
// --known-mass-drives also carries each with a known mass declared at those drives (the true
// mass off by a drawn ticket error of 0.5 %), a heavy truck at --truck-known-mass-drives where
// given (issue 30: two at different loads for a truck);
// --tyre-change-drive fits new tyres (radius 1-3 % larger) before drive K of every life;
// --tyre-change-declared has the workshop say so (vmass-ctl tyres-changed) at its start;
// --trailer-change-drive has each tractor couple another trailer (its load, drag area and
// rolling coefficient drawn) before drive L (--population trucks).
//
// --ablation runs one nominal vehicle with no effect, each effect alone, and all effects.
// --series-dir DIR writes per-tick CSVs (10 Hz) of the runs named by --series RUN,... where
// RUN is VEHICLE:SCENARIO:SEED. --version prints the name and version. Exit codes: 0 ok, 1 a
// run failed, 2 usage or input error. Not installed: it runs in the build tree, beside
// vmass-sim and vmass-accuracy-report (scripts/accuracy-suite.sh).
#include <atomic>
#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "exit_code.hpp"
#include "lifetime_run.hpp"
#include "suite_run.hpp"
#include "vmass/sim/population.hpp"
#include "vmass/sim/population_scenarios.hpp"
#include "vmass/sim/torque_signal_variant.hpp"
#include "vmass/sim/truck_population.hpp"
#include "vmass/sim/vehicle_class.hpp"

namespace fs = std::filesystem;
using vmass::sim::Effect;
using vmass::sim::Realism;

namespace {

using vmass::tools::kExitFailure;
using vmass::tools::kExitUsage;

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

// The first compact car with every input the estimator reads and a passive rear axle.
std::string nominal_vehicle() {
  for (std::uint64_t seed = 1; seed < 10000; ++seed) {
    const auto v = vmass::sim::draw_vehicle(vmass::sim::VehicleClass::kCompact, seed);
    const auto& s = v.sensors;
    if (s.deflection && s.brake_pressure && s.lateral &&
        s.torque == vmass::sim::TorqueSignal::kWheelTorque &&
        s.speed == vmass::sim::SpeedSignal::kEsc && !v.vehicle.rear_levelling &&
        v.vehicle.powertrain.transmission != vmass::sim::Transmission::kElectric) {
      return v.id;
    }
  }
  return "compact-1";
}

struct Options {
  int vehicles = 30;
  std::uint64_t first_seed = 0;  ///< 0: the population's development set
  bool held_out = false;
  int seeds = 3;
  std::string scenarios, estimators, knowledge, realism = "all", estimator_yaml_path, out;
  std::string ablation, series_dir, series, runs;
  int jobs = 0;
  int lifetime_drives = 0;              ///< > 0: the lifetime mode
  std::string known_mass_drives;        ///< --lifetime: drives whose true mass is declared
  std::string truck_known_mass_drives;  ///< --lifetime: the same for heavy trucks ("": the same)
  int tyre_change_drive = 0;            ///< --lifetime: new tyres before this drive (0: never)
  bool tyre_change_declared = false;    ///< --lifetime: ... and the workshop declares them
  int trailer_change_drive = 0;         ///< --lifetime: another trailer before this drive
  int lives = 1;
  std::string keep_dir, vehicle_ids;
  std::string population = "cars";         ///< or trucks (truck_population.hpp)
  std::string torque_signal = "as_drawn";  ///< torque_signal_variant.hpp
};

bool trucks(const Options& o) { return o.population == "trucks"; }

std::vector<std::string> population_scenarios(const Options& o) {
  return trucks(o) ? vmass::sim::truck_scenario_names() : vmass::sim::population_scenario_names();
}

// The ids of --population's development (or held-out) vehicles.
std::vector<std::string> population_ids(const Options& o) {
  std::vector<std::string> ids;
  if (trucks(o)) {
    const std::uint64_t first = o.held_out         ? vmass::sim::kTruckHeldOutFirstSeed
                                : o.first_seed > 0 ? o.first_seed
                                                   : vmass::sim::kTruckFirstSeed;
    for (const auto& v : vmass::sim::draw_truck_population(o.vehicles, first)) ids.push_back(v.id);
    return ids;
  }
  const std::uint64_t first = o.held_out         ? vmass::sim::kHeldOutFirstSeed
                              : o.first_seed > 0 ? o.first_seed
                                                 : vmass::sim::kDevelopmentFirstSeed;
  for (const auto& v : vmass::sim::draw_population(o.vehicles, first)) ids.push_back(v.id);
  return ids;
}

bool parse_knowledge(const std::string& text, std::vector<vmass::sim::Knowledge>* out) {
  out->clear();
  for (const std::string& k : split(text)) {
    if (k == "known_scale") {
      out->push_back(vmass::sim::Knowledge::kKnownScale);
    } else if (k == "datasheet_scale") {
      out->push_back(vmass::sim::Knowledge::kDatasheetScale);
    } else {
      return false;
    }
  }
  return !out->empty();
}

std::string read_text(const std::string& path, bool* ok) {
  std::ifstream in(path, std::ios::binary);
  *ok = static_cast<bool>(in);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The runs named by --runs (VEHICLE:SCENARIO:SEED), each with its series when asked.
std::string plan_runs(const Options& o, const vmass::suite::RunSpec& base,
                      std::vector<vmass::suite::RunSpec>* specs) {
  const auto realism = Realism::parse(o.realism);
  if (!realism) return "--realism: '" + o.realism + "' is not all, none, all-EFFECT or A+B";
  for (const std::string& run : split(o.runs)) {
    const auto a = run.find(':');
    const auto b = run.rfind(':');
    if (a == std::string::npos || a == b)
      return "--runs: '" + run + "' is not VEHICLE:SCENARIO:SEED";
    vmass::suite::RunSpec spec = base;
    spec.vehicle_id = run.substr(0, a) == "nominal" ? nominal_vehicle() : run.substr(0, a);
    spec.scenario = run.substr(a + 1, b - a - 1);
    const std::string seed = run.substr(b + 1);
    if (seed.empty() || seed.find_first_not_of("0123456789") != std::string::npos) {
      return "--runs: '" + run + "': the seed must be a number";
    }
    spec.seed = std::stoull(seed);
    spec.realism = *realism;
    spec.realism_label = o.realism;
    vmass::sim::DrawnVehicle probe;
    std::string error;
    if (!vmass::sim::parse_vehicle_id(spec.vehicle_id, &probe, &error)) return "--runs: " + error;
    if (vmass::sim::population_scenario_description(spec.scenario).empty()) {
      return "--runs: unknown scenario '" + spec.scenario + "'";
    }
    specs->push_back(spec);
  }
  return "";
}

// Expands the options into the list of runs. "" or a usage error.
std::string plan(const Options& o, std::vector<vmass::suite::RunSpec>* specs) {
  vmass::suite::RunSpec base;
  base.estimators = o.estimators.empty() ? vmass::suite::default_estimators() : split(o.estimators);
  if (!o.knowledge.empty() && !parse_knowledge(o.knowledge, &base.knowledge)) {
    return "--knowledge: expected known_scale and/or datasheet_scale";
  }
  const auto torque_signal = vmass::sim::parse_torque_signal_variant(o.torque_signal);
  if (!torque_signal) {
    return "--torque-signal: expected one of " + vmass::sim::torque_signal_variant_names();
  }
  base.torque_signal = *torque_signal;
  if (!o.estimator_yaml_path.empty()) {
    bool ok = false;
    base.estimator_yaml = read_text(o.estimator_yaml_path, &ok);
    if (!ok) return o.estimator_yaml_path + ": cannot read";
  }
  base.series_dir = o.series_dir;
  std::vector<std::string> scenarios =
      o.scenarios.empty() ? population_scenarios(o) : split(o.scenarios);
  for (const std::string& s : scenarios) {
    if (vmass::sim::population_scenario_description(s).empty()) {
      return "--scenarios: unknown scenario '" + s + "'";
    }
  }
  std::vector<std::pair<std::string, Realism>> realisms;
  std::vector<std::string> vehicles;
  if (!o.runs.empty()) return plan_runs(o, base, specs);
  if (!o.ablation.empty()) {
    vehicles.push_back(o.ablation == "auto" ? nominal_vehicle() : o.ablation);
    realisms.emplace_back("none", Realism::none());
    for (Effect e : vmass::sim::all_effects()) {
      realisms.emplace_back("only:" + std::string(vmass::sim::effect_name(e)), Realism::only(e));
    }
    realisms.emplace_back("all", Realism::all());
  } else {
    const auto r = Realism::parse(o.realism);
    if (!r) return "--realism: '" + o.realism + "' is not all, none, all-EFFECT or A+B";
    realisms.emplace_back(o.realism, *r);
    vehicles = population_ids(o);
  }
  for (const std::string& v : vehicles) {
    vmass::sim::DrawnVehicle probe;
    std::string error;
    if (!vmass::sim::parse_vehicle_id(v, &probe, &error)) return "--ablation: " + error;
  }
  for (const auto& [label, realism] : realisms) {
    for (const std::string& v : vehicles) {
      for (const std::string& s : scenarios) {
        for (int seed = 1; seed <= o.seeds; ++seed) {
          vmass::suite::RunSpec spec = base;
          spec.vehicle_id = v;
          spec.scenario = s;
          spec.seed = static_cast<std::uint64_t>(seed);
          spec.realism = realism;
          spec.realism_label = label;
          const std::string id = v + ":" + s + ":" + std::to_string(seed);
          if (o.series.find(id) == std::string::npos) spec.series_dir.clear();
          specs->push_back(spec);
        }
      }
    }
  }
  return "";
}

// A comma-separated list of drive indices 1..drives into *out; "" or what is wrong.
std::string parse_drive_list(const std::string& option, const std::string& text, int drives,
                             std::vector<int>* out) {
  for (const std::string& d : split(text)) {
    int index = 0;
    const auto r = std::from_chars(d.data(), d.data() + d.size(), index);
    if (r.ec != std::errc() || r.ptr != d.data() + d.size() || index < 1 || index > drives) {
      return option + ": '" + d + "' is not a drive index 1.." + std::to_string(drives);
    }
    out->push_back(index);
  }
  return "";
}

// The lifetime mode's lives: every vehicle of the population (or the held-out set), K lives.
std::string plan_lifetimes(const Options& o, std::vector<vmass::suite::LifetimeSpec>* specs) {
  vmass::suite::LifetimeSpec base;
  base.drives = o.lifetime_drives;
  base.keep_dir = o.keep_dir;
  base.series_dir = o.series_dir;
  if (!o.estimators.empty()) base.estimators = split(o.estimators);
  for (const std::string& e : base.estimators) {
    if (e != "rls" && e != "bayes") return "--lifetime: estimator '" + e + "' is not rls or bayes";
  }
  if (!o.knowledge.empty() && !parse_knowledge(o.knowledge, &base.knowledge)) {
    return "--knowledge: expected known_scale and/or datasheet_scale";
  }
  if (!o.estimator_yaml_path.empty()) {
    bool ok = false;
    base.estimator_yaml = read_text(o.estimator_yaml_path, &ok);
    if (!ok) return o.estimator_yaml_path + ": cannot read";
  }
  const auto realism = Realism::parse(o.realism);
  if (!realism) return "--realism: '" + o.realism + "' is not all, none, all-EFFECT or A+B";
  base.realism = *realism;
  base.realism_label = o.realism;
  if (auto m = parse_drive_list("--known-mass-drives", o.known_mass_drives, o.lifetime_drives,
                                &base.known_mass_drives);
      !m.empty()) {
    return m;
  }
  if (auto m = parse_drive_list("--truck-known-mass-drives", o.truck_known_mass_drives,
                                o.lifetime_drives, &base.truck_known_mass_drives);
      !m.empty()) {
    return m;
  }
  if (!base.truck_known_mass_drives.empty() && base.known_mass_drives.empty()) {
    return "--truck-known-mass-drives needs --known-mass-drives";
  }
  if (o.tyre_change_drive != 0 &&
      (o.tyre_change_drive < 2 || o.tyre_change_drive > o.lifetime_drives)) {
    return "--tyre-change-drive: " + std::to_string(o.tyre_change_drive) +
           " is not a drive index 2.." + std::to_string(o.lifetime_drives);
  }
  base.tyre_change_drive = o.tyre_change_drive;
  if (o.tyre_change_declared && o.tyre_change_drive == 0) {
    return "--tyre-change-declared needs --tyre-change-drive";
  }
  base.tyre_change_declared = o.tyre_change_declared;
  if (o.trailer_change_drive != 0 &&
      (o.trailer_change_drive < 2 || o.trailer_change_drive > o.lifetime_drives)) {
    return "--trailer-change-drive: " + std::to_string(o.trailer_change_drive) +
           " is not a drive index 2.." + std::to_string(o.lifetime_drives);
  }
  base.trailer_change_drive = o.trailer_change_drive;
  std::vector<std::string> ids = split(o.vehicle_ids);
  if (ids.empty()) {
    ids = population_ids(o);
  }
  for (const std::string& id : ids) {
    vmass::sim::DrawnVehicle probe;
    std::string error;
    if (!vmass::sim::parse_vehicle_id(id, &probe, &error)) return "--vehicle-ids: " + error;
    if (base.trailer_change_drive != 0 && !probe.tractor) {
      return "--trailer-change-drive: " + id + " pulls no trailer (tractors: --population trucks)";
    }
    for (int life = 1; life <= o.lives; ++life) {
      vmass::suite::LifetimeSpec spec = base;
      spec.vehicle_id = id;
      spec.life = static_cast<std::uint64_t>(life);
      specs->push_back(spec);
    }
  }
  return "";
}

// Runs `count` jobs on `jobs` threads, each in its own work directory; `run(i, dir)` returns
// the JSON lines of job i and an error ("" when it went well). Exit code 0, 1 or 2.
template <class Run>
int run_parallel(std::size_t count, int jobs, const std::string& out_path, Run run) {
  std::ofstream out(out_path, std::ios::trunc);
  if (!out) {
    std::cerr << "vmass-suite: " << out_path << ": cannot write\n";
    return kExitUsage;
  }
  const fs::path work_root =
      fs::temp_directory_path() / ("vmass-suite-" + std::to_string(::getpid()));
  std::atomic<std::size_t> next{0};
  std::atomic<int> failures{0};
  std::mutex out_mutex;
  auto worker = [&](int id) {
    const fs::path dir = work_root / std::to_string(id);
    fs::create_directories(dir);
    for (std::size_t i = next++; i < count; i = next++) {
      std::string error;
      const std::string lines = run(i, dir.string(), &error);
      std::lock_guard<std::mutex> lock(out_mutex);
      if (!error.empty()) {
        ++failures;
        std::cerr << "vmass-suite: " << error << "\n";
      }
      out << lines;
      if ((i + 1) % 25 == 0 || i + 1 == count) {
        std::cerr << "vmass-suite: " << (i + 1) << "/" << count << " runs\n";
      }
    }
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < jobs; ++j) threads.emplace_back(worker, j);
  for (auto& t : threads) t.join();
  std::error_code ec;
  fs::remove_all(work_root, ec);
  out.close();
  if (!out) {
    std::cerr << "vmass-suite: " << out_path << ": write failed\n";
    return kExitFailure;
  }
  return failures > 0 ? kExitFailure : 0;
}

int run_all(const std::vector<vmass::suite::RunSpec>& specs, int jobs,
            const std::string& out_path) {
  return run_parallel(
      specs.size(), jobs, out_path, [&](std::size_t i, const std::string& dir, std::string* error) {
        const vmass::suite::RunResult r = vmass::suite::run_suite_case(specs[i], dir);
        if (!r.error.empty()) {
          *error = specs[i].vehicle_id + " " + specs[i].scenario + " seed " +
                   std::to_string(specs[i].seed) + ": " + r.error;
        }
        return vmass::suite::to_json_lines(r);
      });
}

int run_lifetimes(const std::vector<vmass::suite::LifetimeSpec>& specs, int jobs,
                  const std::string& out_path) {
  return run_parallel(
      specs.size(), jobs, out_path, [&](std::size_t i, const std::string& dir, std::string* error) {
        const vmass::suite::LifetimeResult r = vmass::suite::run_lifetime(specs[i], dir);
        if (!r.error.empty()) {
          *error = specs[i].vehicle_id + " life " + std::to_string(specs[i].life) + ": " + r.error;
        }
        return r.json_lines;
      });
}

// The lifetime mode's options (--lifetime and what only it reads).
void add_lifetime_options(CLI::App& app, Options* o) {
  app.add_option("--lifetime", o->lifetime_drives,
                 "drives per life: each vehicle drive after drive through the state file")
      ->check(CLI::Range(1, 1000));
  app.add_option("--lives", o->lives, "lives per vehicle (--lifetime)")->check(CLI::Range(1, 100));
  app.add_option("--known-mass-drives", o->known_mass_drives,
                 "--lifetime: also carry every variant with a known mass declared at the start "
                 "of these drives (e.g. 1): the true mass off by a ticket error drawn from "
                 "its declared 0.5 % std");
  app.add_option("--truck-known-mass-drives", o->truck_known_mass_drives,
                 "--lifetime, with --known-mass-drives: a heavy truck's drives instead (e.g. "
                 "1,2: two known masses at different loads)");
  app.add_option("--tyre-change-drive", o->tyre_change_drive,
                 "--lifetime: new tyres (radius 1-3 % larger, the config's unchanged) before "
                 "this drive of every life");
  app.add_flag("--tyre-change-declared", o->tyre_change_declared,
               "--lifetime: the workshop declares those tyres (vmass-ctl tyres-changed) at the "
               "start of that drive");
  app.add_option("--trailer-change-drive", o->trailer_change_drive,
                 "--lifetime, tractors: another trailer (its load, drag area and rolling "
                 "coefficient drawn, the config's unchanged) before this drive of every life");
  app.add_option("--vehicle-ids", o->vehicle_ids,
                 "--lifetime: these vehicles (CLASS-SEED,...) instead of the population's");
  app.add_option("--keep-dir", o->keep_dir,
                 "--lifetime: keep each variant's logs, config and state files here");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vmass-suite: the accuracy suite over the vehicle population"};
  Options o;
  bool list = false, hash = false;
  app.add_option("--vehicles", o.vehicles, "population vehicles (classes in turn)")
      ->check(CLI::Range(1, 10000));
  app.add_option("--first-seed", o.first_seed, "seed of the first vehicle");
  app.add_option("--population", o.population,
                 "cars (default: the classes in turn) or trucks (tractors, their own drives)")
      ->check(CLI::IsMember({"cars", "trucks"}));
  app.add_flag("--held-out", o.held_out, "the held-out vehicles (never tune on them)");
  app.add_option("--seeds", o.seeds, "seeds per (vehicle, scenario)")->check(CLI::Range(1, 100));
  app.add_option("--scenarios", o.scenarios, "comma-separated (default: all)");
  app.add_option("--estimators", o.estimators, "comma-separated (default: rls,bayes,baselines)");
  app.add_option("--knowledge", o.knowledge, "known_scale,datasheet_scale (default both)");
  app.add_option("--torque-signal", o.torque_signal,
                 "combustion vehicles' torque: " + vmass::sim::torque_signal_variant_names());
  app.add_option("--realism", o.realism, "effects: all (default), none, all-EFFECT, A+B");
  app.add_option("--estimator-yaml", o.estimator_yaml_path,
                 "YAML appended to every config (an estimator: section to try)");
  app.add_option("--ablation", o.ablation, "VEHICLE or auto: each effect alone on one vehicle");
  app.add_option("--series-dir", o.series_dir, "directory for per-tick CSVs of --series runs");
  app.add_option("--series", o.series, "runs VEHICLE:SCENARIO:SEED,... to write series for");
  app.add_option("--runs", o.runs,
                 "only these runs, VEHICLE:SCENARIO:SEED,... (VEHICLE nominal: "
                 "the ablation's car)");
  add_lifetime_options(app, &o);
  app.add_option("--jobs", o.jobs, "threads (default: all cores)");
  app.add_option("--out", o.out, "JSON lines output");
  app.add_flag("--list-scenarios", list, "list the population scenarios and exit");
  app.add_flag("--population-hash", hash, "print the population definition's hash and exit");
  if (const auto code = vmass::tools::parse_command_line(app, argc, argv)) return *code;
  if (list) {
    for (const auto& n : population_scenarios(o)) {
      std::cout << n << "  " << vmass::sim::population_scenario_description(n) << "\n";
    }
    return 0;
  }
  if (hash) {
    std::cout << vmass::sim::population_definition_hash() << "\n";
    return 0;
  }
  if (o.out.empty()) {
    std::cerr << "vmass-suite: --out FILE is required\n";
    return kExitUsage;
  }
  const int jobs =
      o.jobs > 0 ? o.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (o.lifetime_drives > 0) {
    std::vector<vmass::suite::LifetimeSpec> lives;
    if (auto m = plan_lifetimes(o, &lives); !m.empty()) {
      std::cerr << "vmass-suite: " << m << "\n";
      return kExitUsage;
    }
    if (!o.keep_dir.empty()) fs::create_directories(o.keep_dir);
    if (!o.series_dir.empty()) fs::create_directories(o.series_dir);
    std::cerr << "vmass-suite: " << lives.size() << " lives of " << o.lifetime_drives
              << " drives on " << jobs << " threads, population "
              << vmass::sim::population_definition_hash() << "\n";
    return run_lifetimes(lives, jobs, o.out);
  }
  std::vector<vmass::suite::RunSpec> specs;
  if (auto m = plan(o, &specs); !m.empty()) {
    std::cerr << "vmass-suite: " << m << "\n";
    return kExitUsage;
  }
  if (!o.series_dir.empty()) fs::create_directories(o.series_dir);
  std::cerr << "vmass-suite: " << specs.size() << " runs on " << jobs << " threads, population "
            << vmass::sim::population_definition_hash() << "\n";
  return run_all(specs, jobs, o.out);
}
