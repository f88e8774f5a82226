// vmass-calibrate: rear-right suspension stiffness (and bump stop) from a static ballast test,
// with its uncertainty, the linear range, a config snippet and a plot (issue 5; paper eq. 1-3,
// Fig. 9).
//
//   vmass-calibrate --ballast CSV [--config FILE] [--masses LIST] [--write-config FILE]
//                   [--plot PNG] [--json] [geometry flags] [fit and plateau flags]
//
// --ballast takes a steps CSV (added_mass_<unit>, rear_right_deflection_<unit>; one row per
// sample or step), a time series (time_s, rear_right_deflection_<unit>[, speed_mps], e.g. a
// vmass samples.csv), or a CAN log of the test (candump -l, Vector ASC or BLF, PEAK TRC, ASAM
// MDF4: recognised by its content, runtime/log_frame_source.hpp), decoded
// with the --config file's `can:` section (one interface of it with --interface) and ticked at
// 100 Hz in log time by the runtime's tick
// driver (vmass/runtime/tick_driver.hpp, as in vmass-replay); every tick with a new, valid
// rear_right_deflection frame
// gives one point (time of that frame, deflection, speed when valid); held values are not
// repeated, so the plateau detector's noise estimate sees the sensor's own sample rate. The
// series' standstill plateaus are found and paired with --masses. Exit codes: 0 ok, 1 fit not
// usable (or one the config loader would refuse: nothing is written) or plot failed, 2 usage or
// data error (a value beyond its physical bound included: ballast_csv.hpp).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "exit_code.hpp"
#include "interface_option.hpp"
#include "vmass/calibrate/ballast_csv.hpp"
#include "vmass/calibrate/calibration_report.hpp"
#include "vmass/calibrate/plateau_detector.hpp"
#include "vmass/calibrate/suspension_fit.hpp"
#include "vmass/can/log_format.hpp"
#include "vmass/config/config.hpp"
#include "vmass/io/regular_file.hpp"
#include "vmass/io/sibling_program.hpp"
#include "vmass/runtime/recording.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/signals/signal_table.hpp"

namespace fs = std::filesystem;

namespace {

using vmass::io::shell_quote;
using vmass::io::sibling_program;
using vmass::tools::kExitFailure;
using vmass::tools::kExitUsage;

int fail(const std::string& message, int code = kExitUsage) {
  std::cerr << "vmass-calibrate: error: " << message << "\n";
  return code;
}

// True when the file is a CAN log (candump -l, Vector ASC or BLF, PEAK TRC, ASAM MDF4, ...: the
// format found from its content), not a CSV; false for a file that cannot be read or is no
// regular file (the CSV reader says why).
bool is_can_log(const std::string& path) {
  if (!vmass::io::check_input_file(path, false).empty()) return false;
  std::ifstream in(path, std::ios::binary);
  std::string head(vmass::can::kLogFormatProbeBytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (head.empty()) return false;  // empty: the CSV reader says so
  return vmass::can::detect_log_format(head) != vmass::can::LogFormat::kUnknown;
}

// The deflection series of a CAN log (see the header comment), of its interface `interface`
// alone unless "". "" or a message.
std::string read_log_series(const std::string& path, const std::string& interface,
                            const vmass::Config& config,
                            std::vector<vmass::calibrate::DeflectionPoint>* series,
                            std::string* note) {
  namespace rt = vmass::runtime;
  rt::LogRecording recording = rt::open_log_recording(path, config);
  if (!recording.source) return recording.error;
  if (!interface.empty()) recording.log->select_interface(interface);
  const rt::CanInputSource& source = *recording.source;
  if (!source.table().input_state(vmass::Input::kRearRightDeflection).mapped) {
    return config.file + ": can.inputs.rear_right_deflection: required to calibrate from a log";
  }
  for (const std::string& w : recording.warnings) std::cerr << "vmass-calibrate: " << w << "\n";
  rt::LogFrameSource& log = *recording.log;
  log.on_error([&log](const vmass::can::CandumpError& e) {
    if (log.stats().corrupt <= 10) std::cerr << "vmass-calibrate: " << e.message << "\n";
  });
  // The config's tick rate, as vmassd and vmass-replay sample the same log.
  const double tick_rate_hz = config.pipeline.estimator.differencing.tick_rate_hz;
  vmass::TimeUs last_update_us = -1;
  vmass::TimeUs t0_us = 0;  // T_0, the first frame's time
  rt::UnpacedClock clock;
  rt::TickDriver driver(*recording.source, tick_rate_hz);
  const rt::TickRun run = driver.run(clock, [&](std::int64_t k, vmass::TimeUs t) {
    if (k == 0) t0_us = t;
    const vmass::Sample s = recording.source->sample_at(t);
    if (!s.has(vmass::Input::kRearRightDeflection)) return;
    const vmass::TimeUs t_us =
        source.table().input_state(vmass::Input::kRearRightDeflection).time_us;
    if (t_us == last_update_us) return;  // held, not a new measurement
    last_update_us = t_us;
    vmass::calibrate::DeflectionPoint p;
    p.time_s = static_cast<double>(t_us - t0_us) * 1e-6;
    p.deflection_m = s.rear_right_deflection_m;
    if (s.has(vmass::Input::kSpeed)) p.speed_mps = s.speed_mps;
    series->push_back(p);
  });
  if (const std::string failed = source.read_error(); !failed.empty()) return failed;
  // No frame on --interface (or not one line could be read).
  if (!interface.empty() && !log.no_frames_reason().empty()) return log.no_frames_reason();
  const auto& c = source.table().counters();
  char buf[200];
  std::snprintf(buf, sizeof buf,
                "log: %llu frames (%llu corrupt %ss, %llu unknown id, %llu too short), %lld "
                "ticks, %zu deflection points",
                static_cast<unsigned long long>(log.stats().frames),
                static_cast<unsigned long long>(log.stats().corrupt),
                std::string(log.unit()).c_str(), static_cast<unsigned long long>(c.unknown_id),
                static_cast<unsigned long long>(c.malformed), static_cast<long long>(run.ticks),
                series->size());
  *note = buf;
  if (const rt::InterfaceSelection* selection = log.interface_selection()) {
    *note += "; interface " + selection->name() + ", " + std::to_string(selection->skipped()) +
             " frames of other interfaces skipped";
  }
  if (series->empty()) {
    return path + ": no valid rear_right_deflection in the log (" + std::string(buf) + ")";
  }
  return "";
}

bool write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  return static_cast<bool>(out);
}

struct Options {
  std::string ballast_path, config_path, masses_text, write_config_path, plot_path;
  std::string interface;  ///< --interface: one interface of a CAN log
  bool json = false;
  std::optional<double> wheelbase_m, cg_to_front_axle_m, gravity_mps2, empty_mass_kg;
  vmass::calibrate::SuspensionFitOptions fit;
  vmass::calibrate::PlateauParams plateau;
};

std::optional<int> parse_options(int argc, char** argv, Options* o) {
  CLI::App app{
      "vmass-calibrate: rear suspension stiffness from static ballast steps (paper eq. 1-3)"};
  double min_step_mm = o->plateau.min_step_m * 1e3;
  app.add_option("--ballast", o->ballast_path,
                 "steps CSV (added_mass_kg, rear_right_deflection_mm), time series CSV "
                 "(time_s, rear_right_deflection_<unit>[, speed_mps]) or CAN log (candump -l, "
                 "Vector ASC/BLF, PEAK TRC, ASAM MDF4; with --config: its can: section)")
      ->required();
  app.add_option("--config", o->config_path, "vmass YAML config: vehicle geometry and empty mass");
  vmass::tools::add_interface_option(app, &o->interface);
  app.add_option("--masses", o->masses_text,
                 "ballast added at each plateau of a time series, kg, in time order: "
                 "'0,100,200' or FIRST:STEP:LAST");
  app.add_option("--write-config", o->write_config_path, "write the suspension: YAML snippet here");
  app.add_option("--plot", o->plot_path, "write a PNG: steps, both fits, linear range, residuals");
  app.add_flag("--json", o->json, "print the results as one JSON object on stdout");
  app.add_option("--wheelbase-m", o->wheelbase_m, "l (overrides the config)");
  app.add_option("--cg-to-front-axle-m", o->cg_to_front_axle_m, "l_f (overrides the config)");
  app.add_option("--gravity-mps2", o->gravity_mps2, "g (overrides the config; default 9.80665)");
  app.add_option("--empty-mass-kg", o->empty_mass_kg,
                 "M_idle, for the per-step total-mass table (overrides the config)");
  app.add_option("--linear-tolerance", o->fit.linear_tolerance,
                 "linear range: relative load error allowed (default 0.01)");
  app.add_option("--robust-scale-mm", o->fit.robust_scale_mm,
                 "Cauchy loss scale, mm (default 0: estimated from the residuals)");
  app.add_option("--settle-s", o->plateau.settle_s, "plateaus: settling time always dropped");
  app.add_option("--min-plateau-s", o->plateau.min_plateau_s, "plateaus: shortest plateau kept");
  app.add_option("--min-step-mm", min_step_mm, "plateaus: closer levels are the same load");
  if (const auto code = vmass::tools::parse_command_line(app, argc, argv)) return code;
  o->plateau.min_step_m = min_step_mm * 1e-3;
  return std::nullopt;
}

/// The vehicle's geometry (and empty mass) from the config and the flags.
struct VehicleSetup {
  vmass::VehicleParams vehicle;
  bool have_empty_mass = false;
  std::optional<vmass::Config> config;
};

/// "" or why the geometry cannot be used.
std::string load_vehicle(const Options& o, VehicleSetup* out) {
  if (!o.config_path.empty()) {
    vmass::ConfigLoad loaded = vmass::load_config(o.config_path);
    if (!loaded.ok()) return loaded.error;
    out->vehicle = loaded.config->pipeline.vehicle;
    out->have_empty_mass = true;
    out->config = std::move(loaded.config);
  }
  vmass::VehicleParams& v = out->vehicle;
  if (o.wheelbase_m) v.wheelbase_m = *o.wheelbase_m;
  if (o.cg_to_front_axle_m) v.cg_to_front_axle_m = *o.cg_to_front_axle_m;
  if (o.gravity_mps2) v.gravity_mps2 = *o.gravity_mps2;
  if (o.empty_mass_kg) {
    v.empty_mass_kg = *o.empty_mass_kg;
    out->have_empty_mass = true;
  }
  if (std::string m = vmass::calibrate::LoadGeometry::from_vehicle(v).validate(); !m.empty()) {
    return m + (o.config_path.empty()
                    ? " (give --config FILE, or --wheelbase-m and --cg-to-front-axle-m)"
                    : "");
  }
  if (out->have_empty_mass && !(v.empty_mass_kg > 0.0)) return "vehicle.empty_mass_kg must be > 0";
  return "";
}

/// The ballast file as a steps CSV or a time series (a CSV or a CAN log). "" or an error.
std::string read_ballast(const Options& o, const VehicleSetup& setup,
                         vmass::calibrate::BallastCsvRead* read, std::string* log_note) {
  if (!is_can_log(o.ballast_path)) {
    *read = vmass::calibrate::read_ballast_csv(o.ballast_path);
    if (!read->ok()) return read->error;
    if (!o.interface.empty()) return o.ballast_path + " is a CSV: --interface is for a CAN log";
    return "";
  }
  if (!setup.config) {
    return o.ballast_path +
           " is a CAN log: give --config FILE with the can: section that maps "
           "rear_right_deflection (and speed) from the DBC";
  }
  read->csv = vmass::calibrate::BallastCsv{};
  read->csv->kind = vmass::calibrate::BallastCsvKind::kSeries;
  return read_log_series(o.ballast_path, o.interface, *setup.config, &read->csv->series, log_note);
}

/// The ballast steps: a steps CSV's groups, or a time series' plateaus paired with --masses.
std::string ballast_steps(const Options& o, const VehicleSetup& setup,
                          std::vector<vmass::calibrate::BallastStep>* steps,
                          std::vector<std::string>* notes) {
  namespace cal = vmass::calibrate;
  cal::BallastCsvRead read;
  std::string log_note;
  if (std::string m = read_ballast(o, setup, &read, &log_note); !m.empty()) return m;
  if (read.csv->kind == cal::BallastCsvKind::kSteps) {
    if (!o.masses_text.empty()) {
      return "--masses is for a time series; " + o.ballast_path +
             " already has an added_mass column";
    }
    *steps = cal::group_samples(read.csv->samples);
    return "";
  }
  if (o.masses_text.empty()) {
    return o.ballast_path + " is a time series: give the ballast of each plateau with --masses";
  }
  std::vector<double> masses;
  if (std::string m = cal::parse_mass_list(o.masses_text, &masses); !m.empty()) return m;
  const cal::PlateauDetection detection = cal::detect_plateaus(read.csv->series, o.plateau);
  if (!detection.ok()) return o.ballast_path + ": " + detection.error;
  *notes = detection.notes;
  if (std::string m = cal::steps_from_plateaus(detection.plateaus, masses, steps); !m.empty()) {
    return o.ballast_path + ": " + m;
  }
  char buf[160];
  std::snprintf(buf, sizeof buf, "%zu plateaus found (noise %.4f mm); %ld rows skipped",
                detection.plateaus.size(), detection.noise_std_m * 1e3, read.csv->skipped_rows);
  notes->insert(notes->begin(), buf);
  if (!log_note.empty()) notes->insert(notes->begin(), log_note);
  return "";
}

/// Runs the plotting script on the result's JSON. "" or why it failed.
std::string plot(const Options& o, const std::string& json_text) {
  const std::string json_path =
      (fs::temp_directory_path() / ("vmass-calibrate-" + std::to_string(::getpid()) + ".json"))
          .string();
  if (!write_file(json_path, json_text)) return json_path + ": cannot write";
  const std::string command =
      shell_quote(sibling_program("vmass-calibrate-plot")) + " --result " + shell_quote(json_path) +
      " --out " + shell_quote(o.plot_path) + " --title " +
      shell_quote("vmass-calibrate: " + fs::path(o.ballast_path).filename().string());
  const int rc = std::system(command.c_str());
  fs::remove(json_path);
  return rc == 0 ? "" : "plotting failed (" + command + ")";
}

void print_report(const Options& o, const std::vector<std::string>& notes, const std::string& text,
                  const std::string& snippet) {
  for (const std::string& n : notes) std::cout << "note: " << n << "\n";
  std::cout << text << "\n";
  if (o.write_config_path.empty()) {
    std::cout << snippet;
  } else {
    std::cout << "config snippet     " << o.write_config_path << "\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  namespace cal = vmass::calibrate;
  Options o;
  if (const auto code = parse_options(argc, argv, &o)) return *code;
  VehicleSetup setup;
  if (std::string m = load_vehicle(o, &setup); !m.empty()) return fail(m);
  std::vector<cal::BallastStep> steps;
  std::vector<std::string> notes;
  if (std::string m = ballast_steps(o, setup, &steps, &notes); !m.empty()) return fail(m);
  if (std::string m = cal::check_steps(steps); !m.empty()) return fail(o.ballast_path + ": " + m);

  const cal::SuspensionFitResult result =
      cal::fit_suspension(steps, cal::LoadGeometry::from_vehicle(setup.vehicle), o.fit);
  if (!result.ok()) return fail(result.error, kExitFailure);
  const cal::SuspensionCalibration& c = *result.calibration;
  const std::vector<cal::MassCheckRow> rows =
      setup.have_empty_mass ? cal::mass_check(c, setup.vehicle) : std::vector<cal::MassCheckRow>{};
  const std::string snippet = cal::suspension_yaml(
      c, {"rear-right suspension, written by vmass-calibrate from " +
              fs::path(o.ballast_path).filename().string(),
          "(replace the suspension: section of the vmassd config with this one)"});
  if (std::string m = cal::check_suspension_yaml(snippet); !m.empty()) {
    return fail(o.ballast_path +
                    ": the fitted suspension is not written: the config loader would " +
                    "refuse it (" + m + "); are the masses and deflections in the units " +
                    "their columns name?",
                kExitFailure);
  }
  if (!o.write_config_path.empty() && !write_file(o.write_config_path, snippet)) {
    return fail(o.write_config_path + ": cannot write");
  }
  const std::string json_text = cal::calibration_json(c, rows);
  if (o.json) {
    std::cout << json_text << "\n";
  } else {
    print_report(o, notes, cal::calibration_text(c, rows), snippet);
  }
  if (o.plot_path.empty()) return 0;
  if (std::string m = plot(o, json_text); !m.empty()) {
    return fail(m, m.find("plotting failed") == 0 ? kExitFailure : kExitUsage);
  }
  if (!o.json) std::cout << "plot               " << o.plot_path << "\n";
  return 0;
}
