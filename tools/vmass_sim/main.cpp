// vmass-sim: simulate a named scenario and write what the estimator and its tests need.
//
//   vmass-sim --list
//   vmass-sim --scenario NAME [--seed N] [--noise none|eps1|eps2|eps3] [--ideal-sensors] --out DIR
//   vmass-sim --vehicle CLASS-SEED --scenario NAME [--seed N] [--realism all|none|...]
//             [--knowledge known_scale|datasheet_scale] --out DIR
//   vmass-sim --list-vehicles N [--first-seed S]
//
// Both are drives of the simulator's one front end (vmass/sim/drive.hpp). Without --vehicle, the
// demo car on a named scenario (demo_drive.hpp). With --vehicle, the drive is one of the vehicle
// population's (population_scenarios.hpp) on a drawn vehicle (population.hpp), with every
// real-world effect on unless --realism says otherwise, and DIR gets that vehicle's own DBC, its
// bus log and the config its engineer writes from the datasheet (population_drive.hpp).
//
// Writes DIR/samples.csv, DIR/truth.csv, DIR/config.yaml (docs/formats.md), and the same drive
// on CAN: DIR/drive.log (candump -l) with DIR/vehicle.dbc, which config.yaml's `can:` section
// maps. The same scenario, seed and noise give byte-identical files.
// Exit codes: 0 ok, 2 usage or I/O error.
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <system_error>

#include <CLI/CLI.hpp>

#include "exit_code.hpp"

#include "vmass/sim/demo_drive.hpp"
#include "vmass/sim/drive.hpp"
#include "vmass/sim/population.hpp"
#include "vmass/sim/population_drive.hpp"
#include "vmass/sim/population_scenarios.hpp"
#include "vmass/sim/scenario.hpp"
#include "vmass/sim/simulator.hpp"

namespace {

constexpr int kExitError = 2;

int fail(const std::string& message) {
  std::cerr << "vmass-sim: error: " << message << '\n';
  return kExitError;
}

std::string joined_names() {
  std::string s;
  for (const std::string& n : vmass::sim::scenario_names()) s += (s.empty() ? "" : ", ") + n;
  return s;
}

std::string joined_population_names() {
  std::string s;
  for (const std::string& n : vmass::sim::truck_scenario_names()) {
    s += (s.empty() ? "" : ", ") + n;
  }
  return s;
}

// Simulates the drive and writes its files into dir. "" or a message.
std::string record_and_write(const vmass::sim::DriveSpec& spec, const std::string& dir,
                             vmass::sim::DriveOutput* drive) {
  if (auto m = vmass::sim::record_drive(spec, drive); !m.empty()) return m;
  return vmass::sim::write_drive_files(*drive, dir);
}

struct PopulationArgs {
  std::string vehicle_id, scenario, realism, knowledge, out_dir;
  std::uint64_t seed = 1;
};

int run_population(const PopulationArgs& a) {
  vmass::sim::DrawnVehicle vehicle;
  std::string error;
  if (!vmass::sim::parse_vehicle_id(a.vehicle_id, &vehicle, &error)) return fail(error);
  const auto realism = vmass::sim::Realism::parse(a.realism.empty() ? "all" : a.realism);
  if (!realism)
    return fail("--realism: '" + a.realism + "' is not all, none, all-EFFECT or EFFECT+EFFECT");
  vmass::sim::Knowledge knowledge = vmass::sim::Knowledge::kKnownScale;
  if (a.knowledge == "datasheet_scale") {
    knowledge = vmass::sim::Knowledge::kDatasheetScale;
  } else if (!a.knowledge.empty() && a.knowledge != "known_scale") {
    return fail("--knowledge: expected known_scale or datasheet_scale, got '" + a.knowledge + "'");
  }
  vmass::sim::PopulationRun run;
  if (auto m = vmass::sim::make_population_run(vehicle, a.scenario, a.seed, *realism, &run);
      !m.empty()) {
    return fail(m + " (population scenarios: " + joined_population_names() + ")");
  }
  std::error_code ec;
  std::filesystem::create_directories(a.out_dir, ec);
  if (ec) return fail("cannot create output directory " + a.out_dir + ": " + ec.message());
  vmass::sim::DriveOutput drive;
  if (auto m = record_and_write(vmass::sim::population_drive(vehicle, run, knowledge), a.out_dir,
                                &drive);
      !m.empty()) {
    return fail(m);
  }
  const vmass::sim::SimulationResult& result = drive.result;
  std::cout << "vmass-sim: " << vmass::sim::describe_vehicle(vehicle) << "\n"
            << "vmass-sim: " << run.scenario << ", seed " << a.seed << ", realism "
            << realism->describe() << ", " << vmass::sim::knowledge_name(knowledge) << ": "
            << drive.handover.frames.size() << " frames, mass " << result.truth.front().mass_kg
            << " -> " << result.truth.back().mass_kg << " kg; wrote " << a.out_dir
            << "/{vehicle.dbc,drive.log,config.yaml,truth.csv,samples.csv}\n";
  return 0;
}

// Everything the command line sets.
struct Args {
  bool list = false;
  std::string scenario_name;
  std::uint64_t seed = 1;
  std::string noise_name;
  std::string out_dir;
  bool ideal = false;
  PopulationArgs pop;
  int list_vehicles = 0;
  std::uint64_t first_seed = vmass::sim::kDevelopmentFirstSeed;
};

void add_options(CLI::App& app, Args& a) {
  app.add_flag("--list", a.list, "list the scenarios and exit");
  app.add_option("--scenario", a.scenario_name, "scenario name (see --list)");
  app.add_option("--seed", a.seed, "seed of the sensor noise (default 1)");
  app.add_option("--noise", a.noise_name,
                 "wheel-force noise set: none, eps1 (default), eps2, eps3");
  app.add_flag("--ideal-sensors", a.ideal, "no sensor noise, bias or quantisation (debugging)");
  app.add_option("--out", a.out_dir, "output directory (created if missing)");
  app.add_option("--vehicle", a.pop.vehicle_id, "population vehicle CLASS-SEED (e.g. suv-7)");
  app.add_option("--realism", a.pop.realism, "effects: all (default), none, all-EFFECT, A+B");
  app.add_option("--knowledge", a.pop.knowledge, "known_scale (default) or datasheet_scale");
  app.add_option("--list-vehicles", a.list_vehicles, "list the first N population vehicles");
  app.add_option("--first-seed", a.first_seed, "seed of the first vehicle of --list-vehicles");
}

int list_scenarios() {
  for (const std::string& n : vmass::sim::scenario_names()) {
    const auto s = vmass::sim::find_scenario(n);
    std::cout << n << "  " << s->description << '\n';
  }
  std::cout << "\npopulation scenarios (with --vehicle CLASS-SEED; the truck_ drives are the "
               "truck population's, with --vehicle tractor-SEED):\n";
  for (const std::string& n : vmass::sim::truck_scenario_names()) {
    std::cout << n << "  " << vmass::sim::population_scenario_description(n) << '\n';
  }
  return 0;
}

int list_vehicles(int count, std::uint64_t first_seed) {
  for (const auto& v : vmass::sim::draw_population(count, first_seed)) {
    std::cout << vmass::sim::describe_vehicle(v) << '\n';
  }
  return 0;
}

// A named demo scenario: the demo car, its CSV files, config, DBC and log.
int run_demo_scenario(const Args& a) {
  if (a.scenario_name.empty())
    return fail("--scenario NAME is required (one of: " + joined_names() + ")");
  if (a.out_dir.empty()) return fail("--out DIR is required");
  std::optional<vmass::sim::DriveSpec> spec = vmass::sim::demo_drive(a.scenario_name);
  if (!spec) {
    return fail("unknown scenario '" + a.scenario_name + "' (known: " + joined_names() + ")");
  }
  vmass::sim::SimulationOptions& options = spec->options;
  options.seed = a.seed;
  options.ideal_sensors = a.ideal;
  if (!a.noise_name.empty()) {
    options.noise = vmass::sim::parse_noise_set(a.noise_name);
    if (!options.noise) {
      return fail("unknown noise set '" + a.noise_name + "' (known: none, eps1, eps2, eps3)");
    }
  }
  std::error_code ec;
  std::filesystem::create_directories(a.out_dir, ec);
  if (ec) return fail("cannot create output directory " + a.out_dir + ": " + ec.message());
  if (!std::filesystem::is_directory(a.out_dir, ec)) {
    return fail("output path " + a.out_dir + " is not a directory");
  }
  vmass::sim::DriveOutput drive;
  if (auto m = record_and_write(*spec, a.out_dir, &drive); !m.empty()) return fail(m);
  const vmass::sim::SimulationResult& result = drive.result;
  std::cout << "vmass-sim: " << result.scenario << ", seed " << result.seed << ", noise "
            << vmass::sim::noise_set_name(result.noise) << ": " << result.samples.size()
            << " samples at " << result.tick_rate_hz << " Hz, mass " << result.truth.front().mass_kg
            << " -> " << result.truth.back().mass_kg << " kg; wrote " << a.out_dir
            << "/{samples.csv,truth.csv,config.yaml,drive.log,vehicle.dbc}\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "vmass-sim: simulate a vehicle scenario; writes samples.csv, truth.csv, config.yaml, "
      "drive.log, vehicle.dbc"};
  Args a;
  add_options(app, a);
  if (const auto code = vmass::tools::parse_command_line(app, argc, argv)) return *code;
  if (a.list) return list_scenarios();
  if (a.list_vehicles > 0) return list_vehicles(a.list_vehicles, a.first_seed);
  if (a.pop.vehicle_id.empty()) return run_demo_scenario(a);
  if (a.scenario_name.empty()) {
    return fail("--scenario NAME is required (one of: " + joined_population_names() + ")");
  }
  if (a.out_dir.empty()) return fail("--out DIR is required");
  a.pop.scenario = a.scenario_name;
  a.pop.seed = a.seed;
  a.pop.out_dir = a.out_dir;
  return run_population(a.pop);
}
