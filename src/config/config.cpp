#include "vmass/config/config.hpp"

#include <fstream>
#include <sstream>

#include "vmass/config/suspension_section.hpp"
#include "vmass/config/yaml_reader.hpp"

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
  r.reject_unknown_keys();
}

void read_suspension(YamlReader r, SuspensionParams* s) {
  for (const SuspensionField& field : kSuspensionFields) {
    if (field.required) {
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
  {
    YamlReader s = r.child("static_init");
    StaticInitParams& p = e->static_init;
    s.read("standstill_speed_mps", &p.standstill_speed_mps);
    s.read("settle_s", &p.settle_s);
    s.read("standstill_window_s", &p.standstill_window_s);
    s.read("max_deflection_std_m", &p.max_deflection_std_m);
    s.read("prior_std_kg", &p.prior_std_kg);
    s.read("prior_std_fraction_of_added", &p.prior_std_fraction_of_added);
    s.read("out_of_range_prior_std_kg", &p.out_of_range_prior_std_kg);
    s.read("no_static_prior_std_kg", &p.no_static_prior_std_kg);
    s.read("mu_prior_std_n", &p.mu_prior_std_n);
    s.read("load_change_sigma", &p.load_change_sigma);
    s.read("min_load_change_m", &p.min_load_change_m);
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
    YamlReader s = r.child("supervisor");
    s.read("innovation_gate_sigma", &e->supervisor.innovation_gate_sigma);
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

ConfigLoad parse(const YAML::Node& root, const std::string& file, const std::string& directory) {
  ConfigLoad out;
  try {
    Config c;
    c.file = file;
    c.directory = directory;
    YamlReader top(root, file, "");
    if (!top.has("vehicle")) top.fail("vehicle", "required section is missing");
    if (!top.has("suspension")) top.fail("suspension", "required section is missing");
    read_vehicle(top.child("vehicle"), &c.pipeline.vehicle);
    read_suspension(top.child("suspension"), &c.pipeline.suspension);
    read_estimator(top.child("estimator"), &c.pipeline.estimator);
    c.can = top.raw("can");
    c.lcm = top.raw("lcm");
    c.daemon = top.raw("daemon");
    top.reject_unknown_keys();
    const std::string invalid = c.pipeline.validate();
    if (!invalid.empty()) {
      out.error = file + ": " + invalid;
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

}  // namespace

std::string Config::resolve_path(const std::string& path) const {
  if (path.empty() || path.front() == '/' || directory.empty()) return path;
  return directory + "/" + path;
}

ConfigLoad load_config(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    ConfigLoad out;
    out.error = path + ": cannot open the config file";
    return out;
  }
  std::ostringstream text;
  text << in.rdbuf();
  const auto slash = path.find_last_of('/');
  const std::string directory = slash == std::string::npos ? "." : path.substr(0, slash);
  try {
    return parse(YAML::Load(text.str()), path, directory);
  } catch (const YAML::Exception& e) {
    ConfigLoad out;
    out.error = path + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg;
    return out;
  }
}

ConfigLoad load_config_text(const std::string& text, const std::string& name) {
  try {
    return parse(YAML::Load(text), name, "");
  } catch (const YAML::Exception& e) {
    ConfigLoad out;
    out.error = name + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg;
    return out;
  }
}

}  // namespace vmass
