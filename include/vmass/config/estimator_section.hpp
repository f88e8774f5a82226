// The `estimator:` section of the config (docs/formats.md, docs/estimator.md): a field table per
// parameter struct, and one walk over its nested sections that the loader, the writers and the
// formats-doc test share, so that the schema exists in one place.
//
// Configuration time only; not thread-safe (YAML::Emitter).
#pragma once

#include <array>
#include <string>

#include <yaml-cpp/yaml.h>

#include "vmass/config/field_table.hpp"
#include "vmass/config/yaml_reader.hpp"
#include "vmass/core/pipeline.hpp"

namespace vmass {

inline constexpr std::array<Field<EstimatorParams>, 7> kEstimatorFields{{
    {"type", &EstimatorParams::type},
    {"converged_ci_halfwidth_fraction", &EstimatorParams::converged_ci_halfwidth_fraction},
    {"converged_halfwidth_fraction", &EstimatorParams::converged_halfwidth_fraction},
    {"pair_correlation_ticks", &EstimatorParams::pair_correlation_ticks},
    {"model_error_std_fraction", &EstimatorParams::model_error_std_fraction},
    {"fit_pair_terms", &EstimatorParams::fit_pair_terms},
    {"power_cycle_min_off_s", &EstimatorParams::power_cycle_min_off_s},
}};

/// Written at the estimator's own level (`estimator.tick_rate_hz`), not in a section.
inline constexpr std::array<Field<DifferencingParams>, 3> kDifferencingFields{{
    {"tick_rate_hz", &DifferencingParams::tick_rate_hz},
    {"differencing_dt_s", &DifferencingParams::differencing_dt_s},
    {"filter_cutoff_hz", &DifferencingParams::filter_cutoff_hz},
}};

inline constexpr std::array<Field<StaticInitParams>, 16> kStaticInitFields{{
    {"standstill_speed_mps", &StaticInitParams::standstill_speed_mps},
    {"settle_s", &StaticInitParams::settle_s},
    {"standstill_window_s", &StaticInitParams::standstill_window_s},
    {"max_deflection_std_m", &StaticInitParams::max_deflection_std_m},
    {"prior_std_kg", &StaticInitParams::prior_std_kg},
    {"prior_std_fraction_of_empty", &StaticInitParams::prior_std_fraction_of_empty},
    {"payload_x_min_fraction", &StaticInitParams::payload_x_min_fraction},
    {"payload_x_max_fraction", &StaticInitParams::payload_x_max_fraction},
    {"payload_y_max_fraction", &StaticInitParams::payload_y_max_fraction},
    {"out_of_range_prior_std_kg", &StaticInitParams::out_of_range_prior_std_kg},
    {"no_static_prior_std_kg", &StaticInitParams::no_static_prior_std_kg},
    {"mu_prior_std_n", &StaticInitParams::mu_prior_std_n},
    {"load_change_sigma", &StaticInitParams::load_change_sigma},
    {"min_load_change_kg", &StaticInitParams::min_load_change_kg},
    {"min_load_change_fraction", &StaticInitParams::min_load_change_fraction},
    {"max_grade_change_mps2", &StaticInitParams::max_grade_change_mps2},
}};

inline constexpr std::array<Field<LoadChangeParams>, 9> kLoadChangeFields{{
    {"detect_in_motion", &LoadChangeParams::detect_in_motion},
    {"min_stop_s", &LoadChangeParams::min_stop_s},
    {"decide_sigma", &LoadChangeParams::decide_sigma},
    {"min_change_fraction", &LoadChangeParams::min_change_fraction},
    {"min_pairs", &LoadChangeParams::min_pairs},
    {"batch_size", &LoadChangeParams::batch_size},
    {"differencing_dt_s", &LoadChangeParams::differencing_dt_s},
    {"filter_cutoff_hz", &LoadChangeParams::filter_cutoff_hz},
    {"change_prior", &LoadChangeParams::change_prior},
}};

inline constexpr std::array<Field<LongitudinalParams>, 17> kLongitudinalFields{{
    {"enabled", &LongitudinalParams::enabled},
    {"max_abs_accel_y_mps2", &LongitudinalParams::max_abs_accel_y_mps2},
    {"min_abs_delta_accel_x_mps2", &LongitudinalParams::min_abs_delta_accel_x_mps2},
    {"min_abs_delta_force_n", &LongitudinalParams::min_abs_delta_force_n},
    {"min_speed_mps", &LongitudinalParams::min_speed_mps},
    {"weight", &LongitudinalParams::weight},
    {"min_excitation_sigma", &LongitudinalParams::min_excitation_sigma},
    {"settle_s", &LongitudinalParams::settle_s},
    {"converter_shift_settle_s", &LongitudinalParams::converter_shift_settle_s},
    {"use_braking", &LongitudinalParams::use_braking},
    {"use_overrun", &LongitudinalParams::use_overrun},
    {"brake_applied_weight_fraction", &LongitudinalParams::brake_applied_weight_fraction},
    {"noise_memory_s", &LongitudinalParams::noise_memory_s},
    {"subtract_aero", &LongitudinalParams::subtract_aero},
    {"accel_source", &LongitudinalParams::accel_source},
    {"scale_memory_s", &LongitudinalParams::scale_memory_s},
    {"rotating_accel_source", &LongitudinalParams::rotating_accel_source},
}};

inline constexpr std::array<Field<LagParams>, 7> kLagFields{{
    {"enabled", &LagParams::enabled},
    {"max_lag_s", &LagParams::max_lag_s},
    {"memory_s", &LagParams::memory_s},
    {"min_correlation", &LagParams::min_correlation},
    {"min_evidence_s", &LagParams::min_evidence_s},
    {"fixed_lag_s", &LagParams::fixed_lag_s},
    {"provisional_std_s", &LagParams::provisional_std_s},
}};

inline constexpr std::array<Field<DrivelineModeParams>, 11> kDrivelineModeFields{{
    {"enabled", &DrivelineModeParams::enabled},
    {"min_hz", &DrivelineModeParams::min_hz},
    {"max_hz", &DrivelineModeParams::max_hz},
    {"candidates", &DrivelineModeParams::candidates},
    {"damping_ratio", &DrivelineModeParams::damping_ratio},
    {"band_low_hz", &DrivelineModeParams::band_low_hz},
    {"band_high_hz", &DrivelineModeParams::band_high_hz},
    {"max_lag_s", &DrivelineModeParams::max_lag_s},
    {"min_evidence_s", &DrivelineModeParams::min_evidence_s},
    {"min_correlation", &DrivelineModeParams::min_correlation},
    {"min_correlation_gain", &DrivelineModeParams::min_correlation_gain},
}};

inline constexpr std::array<Field<LateralParams>, 7> kLateralFields{{
    {"enabled", &LateralParams::enabled},
    {"max_abs_accel_y_mps2", &LateralParams::max_abs_accel_y_mps2},
    {"min_abs_delta_accel_y_mps2", &LateralParams::min_abs_delta_accel_y_mps2},
    {"max_abs_accel_x_mps2", &LateralParams::max_abs_accel_x_mps2},
    {"min_abs_steering_wheel_angle_deg", &LateralParams::min_abs_steering_wheel_angle_deg},
    {"min_speed_mps", &LateralParams::min_speed_mps},
    {"weight", &LateralParams::weight},
}};

inline constexpr std::array<Field<LateralVelocityFilterParams>, 6> kVelocityFilterFields{{
    {"accel_noise_std_mps2", &LateralVelocityFilterParams::accel_noise_std_mps2},
    {"speed_noise_std_mps", &LateralVelocityFilterParams::speed_noise_std_mps},
    {"pseudo_lateral_velocity_std_mps",
     &LateralVelocityFilterParams::pseudo_lateral_velocity_std_mps},
    {"initial_lateral_velocity_std_mps",
     &LateralVelocityFilterParams::initial_lateral_velocity_std_mps},
    {"accel_x_offset_walk_mps2_per_sqrt_s",
     &LateralVelocityFilterParams::accel_x_offset_walk_mps2_per_sqrt_s},
    {"initial_accel_x_offset_std_mps2",
     &LateralVelocityFilterParams::initial_accel_x_offset_std_mps2},
}};

inline constexpr std::array<Field<SupervisorParams>, 4> kSupervisorFields{{
    {"innovation_gate_sigma", &SupervisorParams::innovation_gate_sigma},
    {"huber_k", &SupervisorParams::huber_k},
    {"min_pairs_before_gating", &SupervisorParams::min_pairs_before_gating},
    {"max_consecutive_rejections", &SupervisorParams::max_consecutive_rejections},
}};

inline constexpr std::array<Field<RlsParams>, 3> kRlsFields{{
    {"noise_std_n", &RlsParams::noise_std_n},
    {"forgetting_factor", &RlsParams::forgetting_factor},
    {"min_variance_fraction", &RlsParams::min_variance_fraction},
}};

inline constexpr std::array<Field<BayesParams>, 4> kBayesFields{{
    {"batch_size", &BayesParams::batch_size},
    {"noise_std_guess_n", &BayesParams::noise_std_guess_n},
    {"prior_noise_dof", &BayesParams::prior_noise_dof},
    {"credible_level", &BayesParams::credible_level},
}};

inline constexpr std::array<Field<LearningParams>, 10> kLearningFields{{
    {"drift_std_per_drive", &LearningParams::drift_std_per_drive},
    {"outlier_sigma", &LearningParams::outlier_sigma},
    {"min_evidence_pairs", &LearningParams::min_evidence_pairs},
    {"max_evidence_std_fraction", &LearningParams::max_evidence_std_fraction},
    {"anchor_prior_std_fraction", &LearningParams::anchor_prior_std_fraction},
    {"max_abs_log_scale", &LearningParams::max_abs_log_scale},
    {"drive_error_std_fraction", &LearningParams::drive_error_std_fraction},
    {"learn_gear_masses", &LearningParams::learn_gear_masses},
    {"min_gear_evidence_pairs", &LearningParams::min_gear_evidence_pairs},
    {"tyre_change_std_fraction", &LearningParams::tyre_change_std_fraction},
}};

inline constexpr std::array<Field<TyreWatchParams>, 7> kTyreWatchFields{{
    {"enabled", &TyreWatchParams::enabled},
    {"launch_std", &TyreWatchParams::launch_std},
    {"min_launches_for_spread", &TyreWatchParams::min_launches_for_spread},
    {"min_launches_each_side", &TyreWatchParams::min_launches_each_side},
    {"change_sigma", &TyreWatchParams::change_sigma},
    {"min_change_fraction", &TyreWatchParams::min_change_fraction},
    {"suspect_sigma", &TyreWatchParams::suspect_sigma},
}};

/// The section's layout: `v.fields(table, params)` for the keys of one level, `v.begin(key)` and
/// `v.end()` around a nested section. `E` is EstimatorParams or const EstimatorParams.
template <class Visitor, class E>
void walk_estimator_section(Visitor& v, E& e) {
  v.fields(kEstimatorFields, e);
  v.fields(kDifferencingFields, e.differencing);
  v.begin("static_init");
  v.fields(kStaticInitFields, e.static_init);
  v.end();
  v.begin("load_change");
  v.fields(kLoadChangeFields, e.load_change);
  v.end();
  v.begin("longitudinal");
  v.fields(kLongitudinalFields, e.longitudinal);
  v.begin("lag");
  v.fields(kLagFields, e.longitudinal.lag);
  v.end();
  v.begin("driveline_mode");
  v.fields(kDrivelineModeFields, e.longitudinal.driveline_mode);
  v.end();
  v.end();
  v.begin("lateral");
  v.fields(kLateralFields, e.lateral);
  v.begin("velocity_filter");
  v.fields(kVelocityFilterFields, e.lateral.velocity_filter);
  v.end();
  v.end();
  v.begin("supervisor");
  v.fields(kSupervisorFields, e.supervisor);
  v.end();
  v.begin("rls");
  v.fields(kRlsFields, e.rls);
  v.end();
  v.begin("bayes");
  v.fields(kBayesFields, e.bayes);
  v.end();
  v.begin("learning");
  v.fields(kLearningFields, e.learning);
  v.begin("tyre_watch");
  v.fields(kTyreWatchFields, e.learning.tyre_watch);
  v.end();
  v.end();
}

/// Reads the section (absent: all defaults); unknown keys are errors at every level. Throws
/// ConfigError.
void read_estimator_section(YamlReader r, EstimatorParams* params);

/// Emits `estimator` and every key of it (the walk's order) into an emitter that is inside a
/// map; the emitter's double precision applies.
void emit_estimator_section(YAML::Emitter& out, const EstimatorParams& params);

}  // namespace vmass
