#include "vmass/config/config.hpp"

#include <algorithm>
#include <sstream>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include "vmass/config/suspension_section.hpp"
#include "vmass/config/yaml_reader.hpp"
#include "vmass/config/yaml_tree.hpp"
#include "vmass/io/regular_file.hpp"

namespace vmass {
namespace {

void read_vehicle(YamlReader r, VehicleParams* v) {
  r.require("empty_mass_kg", &v->empty_mass_kg);
  r.require("wheelbase_m", &v->wheelbase_m);
  r.require("cg_to_front_axle_m", &v->cg_to_front_axle_m);
  r.require("wheel_radius_m", &v->wheel_radius_m);
  r.require("brake_gain_n_per_pa", &v->brake_gain_n_per_pa);
  r.require("steering_ratio", &v->steering_ratio);
  r.require("cornering_stiffness_front_n_per_rad", &v->cornering_stiffness_front_n_per_rad);
  r.require("cornering_stiffness_rear_n_per_rad", &v->cornering_stiffness_rear_n_per_rad);
  r.read("rotating_mass_kg", &v->rotating_mass_kg);
  r.read("rotating_mass_by_gear_kg", &v->rotating_mass_by_gear_kg);
  r.read("gravity_mps2", &v->gravity_mps2);
  r.read("max_mass_kg", &v->max_mass_kg);
  r.read("drag_area_m2", &v->drag_area_m2);
  r.read("air_density_kg_per_m3", &v->air_density_kg_per_m3);
  r.read("rolling_resistance_coeff", &v->rolling_resistance_coeff);
  r.read("wheel_torque_accuracy_fraction", &v->wheel_torque_accuracy_fraction);
  r.read("wheel_radius_accuracy_fraction", &v->wheel_radius_accuracy_fraction);
  r.read("pitch_gradient_deg_per_g", &v->pitch_gradient_deg_per_g);
  r.read("pitch_gradient_std_deg_per_g", &v->pitch_gradient_std_deg_per_g);
  r.read("rotating_mass_accuracy_fraction", &v->rotating_mass_accuracy_fraction);
  r.read("electric_drive", &v->electric_drive);
  r.read("gear_ratios", &v->gear_ratios);
  r.read("final_drive_ratio", &v->final_drive_ratio);
  r.read("driveline_efficiency", &v->driveline_efficiency);
  r.read("max_driveline_slip_fraction", &v->max_driveline_slip_fraction);
  r.reject_unknown_keys();
}

// No section: the car has no rear deflection sensor (the estimator starts from the no-static
// prior). `levelled: true`: it has one on a self-levelling axle, which reads no load.
void read_suspension(YamlReader r, bool present, SuspensionParams* s) {
  s->has_sensor = present;
  if (!present) return;
  r.read("levelled", &s->levelled);
  for (const SuspensionField& field : kSuspensionFields) {
    if (field.required && !s->levelled) {
      r.require(field.key, &(s->*field.member));
    } else {
      r.read(field.key, &(s->*field.member));
    }
  }
  r.reject_unknown_keys();
}

// Over 80 lines: one read per key of the estimator section. Main adds keys here (issue 8);
// then a field table, as vmass/config/suspension_section.hpp, shortens it.
// NOLINTNEXTLINE(readability-function-size)
void read_estimator(YamlReader r, EstimatorParams* e) {
  std::string type = std::string(regressor_type_name(e->type));
  r.read("type", &type);
  if (type == "rls") {
    e->type = RegressorType::kRls;
  } else if (type == "bayes") {
    e->type = RegressorType::kBayes;
  } else {
    r.fail("type", "expected 'rls' or 'bayes', got '" + type + "'");
  }
  r.read("tick_rate_hz", &e->differencing.tick_rate_hz);
  r.read("differencing_dt_s", &e->differencing.differencing_dt_s);
  r.read("filter_cutoff_hz", &e->differencing.filter_cutoff_hz);
  r.read("converged_ci_halfwidth_fraction", &e->converged_ci_halfwidth_fraction);
  r.read("pair_correlation_ticks", &e->pair_correlation_ticks);
  r.read("model_error_std_fraction", &e->model_error_std_fraction);
  r.read("power_cycle_min_off_s", &e->power_cycle_min_off_s);
  {
    YamlReader s = r.child("static_init");
    StaticInitParams& p = e->static_init;
    s.read("standstill_speed_mps", &p.standstill_speed_mps);
    s.read("settle_s", &p.settle_s);
    s.read("standstill_window_s", &p.standstill_window_s);
    s.read("max_deflection_std_m", &p.max_deflection_std_m);
    s.read("prior_std_kg", &p.prior_std_kg);
    s.read("prior_std_fraction_of_empty", &p.prior_std_fraction_of_empty);
    s.read("payload_x_min_fraction", &p.payload_x_min_fraction);
    s.read("payload_x_max_fraction", &p.payload_x_max_fraction);
    s.read("payload_y_max_fraction", &p.payload_y_max_fraction);
    s.read("out_of_range_prior_std_kg", &p.out_of_range_prior_std_kg);
    s.read("no_static_prior_std_kg", &p.no_static_prior_std_kg);
    s.read("mu_prior_std_n", &p.mu_prior_std_n);
    s.read("load_change_sigma", &p.load_change_sigma);
    s.read("min_load_change_kg", &p.min_load_change_kg);
    s.read("min_load_change_fraction", &p.min_load_change_fraction);
    s.read("max_grade_change_mps2", &p.max_grade_change_mps2);
    s.reject_unknown_keys();
  }
  {
    YamlReader s = r.child("longitudinal");
    LongitudinalParams& p = e->longitudinal;
    s.read("enabled", &p.enabled);
    s.read("max_abs_accel_y_mps2", &p.max_abs_accel_y_mps2);
    s.read("min_abs_delta_accel_x_mps2", &p.min_abs_delta_accel_x_mps2);
    s.read("min_abs_delta_force_n", &p.min_abs_delta_force_n);
    s.read("min_speed_mps", &p.min_speed_mps);
    s.read("weight", &p.weight);
    s.read("min_excitation_sigma", &p.min_excitation_sigma);
    s.read("settle_s", &p.settle_s);
    s.read("use_braking", &p.use_braking);
    s.read("use_overrun", &p.use_overrun);
    s.read("brake_applied_weight_fraction", &p.brake_applied_weight_fraction);
    s.read("noise_memory_s", &p.noise_memory_s);
    s.read("subtract_aero", &p.subtract_aero);
    std::string source(accel_source_name(p.accel_source));
    s.read("accel_source", &source);
    if (source == "accelerometer") {
      p.accel_source = AccelSource::kAccelerometer;
    } else if (source == "wheel_speed") {
      p.accel_source = AccelSource::kWheelSpeed;
    } else if (source == "calibrated") {
      p.accel_source = AccelSource::kCalibrated;
    } else {
      s.fail("accel_source",
             "expected accelerometer, wheel_speed or calibrated, got '" + source + "'");
    }
    s.read("scale_memory_s", &p.scale_memory_s);
    YamlReader lag = s.child("lag");
    lag.read("enabled", &p.lag.enabled);
    lag.read("max_lag_s", &p.lag.max_lag_s);
    lag.read("memory_s", &p.lag.memory_s);
    lag.read("min_correlation", &p.lag.min_correlation);
    lag.read("min_evidence_s", &p.lag.min_evidence_s);
    lag.read("fixed_lag_s", &p.lag.fixed_lag_s);
    lag.read("provisional_std_s", &p.lag.provisional_std_s);
    lag.reject_unknown_keys();
    s.reject_unknown_keys();
  }
  {
    YamlReader s = r.child("lateral");
    LateralParams& p = e->lateral;
    s.read("enabled", &p.enabled);
    s.read("max_abs_accel_y_mps2", &p.max_abs_accel_y_mps2);
    s.read("min_abs_delta_accel_y_mps2", &p.min_abs_delta_accel_y_mps2);
    s.read("max_abs_accel_x_mps2", &p.max_abs_accel_x_mps2);
    s.read("min_abs_steering_wheel_angle_deg", &p.min_abs_steering_wheel_angle_deg);
    s.read("min_speed_mps", &p.min_speed_mps);
    s.read("weight", &p.weight);
    YamlReader f = s.child("velocity_filter");
    f.read("accel_noise_std_mps2", &p.velocity_filter.accel_noise_std_mps2);
    f.read("speed_noise_std_mps", &p.velocity_filter.speed_noise_std_mps);
    f.read("pseudo_lateral_velocity_std_mps", &p.velocity_filter.pseudo_lateral_velocity_std_mps);
    f.read("initial_lateral_velocity_std_mps", &p.velocity_filter.initial_lateral_velocity_std_mps);
    f.read("accel_x_offset_walk_mps2_per_sqrt_s",
           &p.velocity_filter.accel_x_offset_walk_mps2_per_sqrt_s);
    f.read("initial_accel_x_offset_std_mps2", &p.velocity_filter.initial_accel_x_offset_std_mps2);
    f.reject_unknown_keys();
    s.reject_unknown_keys();
  }
  {
    YamlReader s = r.child("load_change");
    LoadChangeParams& p = e->load_change;
    s.read("detect_in_motion", &p.detect_in_motion);
    s.read("min_stop_s", &p.min_stop_s);
    s.read("decide_sigma", &p.decide_sigma);
    s.read("min_change_fraction", &p.min_change_fraction);
    int min_pairs = static_cast<int>(p.min_pairs);
    s.read("min_pairs", &min_pairs);
    p.min_pairs = min_pairs;
    s.read("batch_size", &p.batch_size);
    s.read("differencing_dt_s", &p.differencing_dt_s);
    s.read("filter_cutoff_hz", &p.filter_cutoff_hz);
    s.reject_unknown_keys();
  }
  {
    YamlReader s = r.child("supervisor");
    s.read("innovation_gate_sigma", &e->supervisor.innovation_gate_sigma);
    s.read("huber_k", &e->supervisor.huber_k);
    s.read("min_pairs_before_gating", &e->supervisor.min_pairs_before_gating);
    s.read("max_consecutive_rejections", &e->supervisor.max_consecutive_rejections);
    s.reject_unknown_keys();
  }
  {
    YamlReader s = r.child("rls");
    s.read("noise_std_n", &e->rls.noise_std_n);
    s.read("forgetting_factor", &e->rls.forgetting_factor);
    s.read("min_variance_fraction", &e->rls.min_variance_fraction);
    s.reject_unknown_keys();
  }
  {
    YamlReader s = r.child("bayes");
    s.read("batch_size", &e->bayes.batch_size);
    s.read("noise_std_guess_n", &e->bayes.noise_std_guess_n);
    s.read("prior_noise_dof", &e->bayes.prior_noise_dof);
    s.read("credible_level", &e->bayes.credible_level);
    s.reject_unknown_keys();
  }
  r.reject_unknown_keys();
}

/// PipelineParams::validate()'s "key what; key what" as "file:line: key: what" lines, the line
/// being where the key is written (or its section, for a key left at its default).
std::string located(const std::string& invalid, const YAML::Node& root, const std::string& file) {
  std::string out;
  std::size_t begin = 0;
  while (begin < invalid.size()) {
    std::size_t end = invalid.find("; ", begin);
    if (end == std::string::npos) end = invalid.size();
    const std::string one = invalid.substr(begin, end - begin);
    const std::size_t space = one.find(' ');
    std::string key = one.substr(0, space);
    int line = line_of_key(root, key);
    // The estimator's sub-sections name their keys from the section down ("rls.forgetting_factor").
    if (line == 0 && line_of_key(root, "estimator." + key) > 0) {
      key = "estimator." + key;
      line = line_of_key(root, key);
    }
    if (!out.empty()) out += "\n";
    out += file + (line > 0 ? ":" + std::to_string(line) : "") + ": " + key + ":" +
           (space == std::string::npos ? "" : one.substr(space));
    begin = end + 2;
  }
  return out;
}

ConfigLoad parse(const YAML::Node& root, const std::string& file, const std::string& directory) {
  ConfigLoad out;
  try {
    if (std::string duplicate = duplicate_key_error(root, file); !duplicate.empty()) {
      out.error = std::move(duplicate);
      return out;
    }
    Config c;
    c.file = file;
    c.directory = directory;
    YamlReader top(root, file, "");
    if (!top.has("vehicle")) top.fail("vehicle", "required section is missing");
    read_vehicle(top.child("vehicle"), &c.pipeline.vehicle);
    const bool has_suspension = top.has("suspension");
    read_suspension(top.child("suspension"), has_suspension, &c.pipeline.suspension);
    read_estimator(top.child("estimator"), &c.pipeline.estimator);
    c.can = top.raw("can");
    c.lcm = top.raw("lcm");
    c.daemon = top.raw("daemon");
    top.reject_unknown_keys();
    const std::string invalid = c.pipeline.validate();
    if (!invalid.empty()) {
      out.error = located(invalid, root, file);
      return out;
    }
    out.config = std::move(c);
  } catch (const ConfigError& e) {
    out.error = e.what();
  } catch (const YAML::Exception& e) {
    out.error = file + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg;
  }
  return out;
}

/// Counts where documents start, and nothing else.
class DocumentStarts : public YAML::EventHandler {
 public:
  int line = 0;  ///< 1-based
  void OnDocumentStart(const YAML::Mark& mark) override { line = mark.line + 1; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

/// The line of the text's second YAML document, 0 when it holds at most one. Parses at most two
/// documents: yaml-cpp's LoadAll, asked for all of them, never ends on some texts (the fuzzer
/// found one that filled 2 GB with empty documents).
int second_document_line(const std::string& text) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  DocumentStarts first;
  if (!parser.HandleNextDocument(first)) return 0;
  DocumentStarts second;
  return parser.HandleNextDocument(second) ? std::max(second.line, 1) : 0;
}

ConfigLoad failed(const std::string& error) {
  ConfigLoad out;
  out.error = error;
  return out;
}

/// The one YAML document of a config: a second one (after `---`, or anything after `...`) would
/// be read by nobody, so it is an error; so is a NUL byte, which is no YAML text.
ConfigLoad parse_text(const std::string& text, const std::string& file,
                      const std::string& directory) {
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos) {
    const auto line = std::count(text.begin(), text.begin() + static_cast<long>(nul), '\n') + 1;
    return failed(file + ":" + std::to_string(line) + ": a NUL byte: not a YAML config");
  }
  try {
    if (const int line = second_document_line(text); line > 0) {
      return failed(file + ":" + std::to_string(line) +
                    ": a second YAML document: a config is one (nothing after '---' or '...')");
    }
    return parse(YAML::Load(text), file, directory);
  } catch (const YAML::Exception& e) {
    return failed(file + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

}  // namespace

std::string Config::resolve_path(const std::string& path) const {
  if (path.empty() || path.front() == '/' || directory.empty()) return path;
  return directory + "/" + path;
}

ConfigLoad load_config(const std::string& path) {
  const io::FileText text = io::read_regular_file(path, io::kMaxConfigBytes, "config");
  if (!text.ok()) {
    ConfigLoad out;
    out.error = text.error;
    return out;
  }
  if (text.text.find_first_not_of(" \t\r\n") == std::string::npos) {
    ConfigLoad out;
    out.error = path + ": empty file: expected a vmass config (docs/formats.md)";
    return out;
  }
  const auto slash = path.find_last_of('/');
  const std::string directory = slash == std::string::npos ? "." : path.substr(0, slash);
  return parse_text(text.text, path, directory);
}

ConfigLoad load_config_text(const std::string& text, const std::string& name) {
  return parse_text(text, name, "");
}

}  // namespace vmass
