// The population's ranges as data: one literal per vehicle class (in VehicleClass order) and
// the ranges every class shares, each field in its struct's order with its name beside it, and
// every range with its source (vehicle_class.hpp). Read only through vehicle_classes(),
// class_definition() and common_ranges(); population_definition_text() prints all of it.
#include "vmass/sim/vehicle_class.hpp"

namespace vmass::sim {

namespace {

using T = Transmission;
using A = DrivenAxle;

const std::vector<ClassDefinition> kClassTable = {
    {
        VehicleClass::kCityCar,                                   // id
        "VW up!, Fiat 500, Toyota Aygo, Renault Zoe (electric)",  // examples
        {900, 1200, "[TA]"},                                      // empty_mass_kg
        {0.15, 0.30, "[TA] electric variants (Zoe, e-up!)"},      // electric_extra_mass_fraction
        {350, 450, "[TA]"},                                       // payload_capacity_kg
        {2.30, 2.55, "[TA]"},                                     // wheelbase_m
        {1.38, 1.50, "[TA]"},                                     // track_m
        {0.59, 0.64, "[GIL] front-engined front-wheel drive"},    // front_weight_share
        {0.50, 0.57, "[GIL]"},                                    // cg_height_m
        {0.60, 0.70, "[HUCHO]"},                                  // drag_area_m2
        {0.009, 0.012, "[WONG]"},                                 // rolling_f0
        {3e-6, 6e-6, "[J2452]"},                                  // rolling_f2_s2_per_m2
        {0.5, 1.5, "[WONG] ~1-3 % of drive power at speed"},      // driveline_viscous_n_per_mps
        {0.27, 0.30, "[TA] 165/65 R14 - 185/55 R15"},             // wheel_radius_m
        {45, 80, "[TA]"},                                         // power_kw
        {2.6, 3.6, "[ours] four 0.6-0.8 kg m^2 wheels with discs, shafts"},  // wheel_inertia_kgm2
        {0.08, 0.15, "[ours] 1.0-1.2 l engines with flywheel"},              // engine_inertia_kgm2
        {14, 17, "[TA]"},                                                    // steering_ratio
        {14, 19, "[PAC]"},                                  // cornering_per_load_front
        {17, 23, "[PAC]"},                                  // cornering_per_load_rear
        3500,                                               // tyre_reference_load_n
        {17000, 24000, "[GIL] ride frequency 1.2-1.5 Hz"},  // rear_wheel_rate_n_per_m
        {3.0, 5.0, "[RCVD] passenger cars"},                // roll_gradient_deg_per_g
        {0.8, 1.6, "[RCVD]"},                               // pitch_gradient_deg_per_g
        {2.0, 4.0, "[CRO]"},                                // mode_first_gear_hz
        {6.0, 10.0, "[CRO]"},                               // mode_top_gear_hz
        {0.03, 0.07,
         "[ours] light car on a smooth road, after the IMU mount"},  // vibration_rms_mps2
        {90, 130, "[GIL] [LIMP]"},                                   // brake_full_pressure_bar
        {{T::kManual, 0.45},
         {T::kAutomatedManual, 0.1},
         {T::kDualClutch, 0.15},
         {T::kElectric, 0.3}},  // transmissions
        {{A::kFront, 1.0}},     // driven_axles
        0.3,                    // p_deflection_sensor
        0.85,                   // p_brake_pressure
        0.2,                    // p_engine_torque_only
        0.0,                    // p_levelling
        0.15,                   // p_display_speed_only
        0.03,                   // p_no_lateral
    },
    {
        VehicleClass::kCompact,                                          // id
        "VW Golf VIII, Ford Focus, Toyota Corolla, VW ID.3 (electric)",  // examples
        {1200, 1500, "[TA]"},                                            // empty_mass_kg
        {0.20, 0.35, "[TA]"},                          // electric_extra_mass_fraction
        {450, 560, "[TA]"},                            // payload_capacity_kg
        {2.55, 2.75, "[TA]"},                          // wheelbase_m
        {1.50, 1.60, "[TA]"},                          // track_m
        {0.57, 0.63, "[GIL]"},                         // front_weight_share
        {0.50, 0.57, "[GIL]"},                         // cg_height_m
        {0.60, 0.70, "[HUCHO]"},                       // drag_area_m2
        {0.008, 0.011, "[WONG]"},                      // rolling_f0
        {3e-6, 6e-6, "[J2452]"},                       // rolling_f2_s2_per_m2
        {0.5, 2.0, "[WONG]"},                          // driveline_viscous_n_per_mps
        {0.30, 0.33, "[TA] 205/55 R16 - 225/45 R17"},  // wheel_radius_m
        {80, 150, "[TA]"},                             // power_kw
        {3.2, 4.4, "[ours]"},                          // wheel_inertia_kgm2
        {0.12, 0.22, "[ours]"},                        // engine_inertia_kgm2
        {13.5, 16.5, "[TA]"},                          // steering_ratio
        {15, 20, "[PAC]"},                             // cornering_per_load_front
        {18, 24, "[PAC]"},                             // cornering_per_load_rear
        4000,                                          // tyre_reference_load_n
        {20000, 30000, "[GIL]"},                       // rear_wheel_rate_n_per_m
        {2.8, 4.5, "[RCVD]"},                          // roll_gradient_deg_per_g
        {0.7, 1.5, "[RCVD]"},                          // pitch_gradient_deg_per_g
        {2.0, 4.0, "[CRO]"},                           // mode_first_gear_hz
        {6.0, 10.0, "[CRO]"},                          // mode_top_gear_hz
        {0.02, 0.06, "[ours]"},                        // vibration_rms_mps2
        {90, 130, "[GIL] [LIMP]"},                     // brake_full_pressure_bar
        {{T::kManual, 0.3},
         {T::kDualClutch, 0.3},
         {T::kAutomatic, 0.15},
         {T::kElectric, 0.25}},              // transmissions
        {{A::kFront, 0.9}, {A::kAll, 0.1}},  // driven_axles
        0.45,                                // p_deflection_sensor
        0.9,                                 // p_brake_pressure
        0.15,                                // p_engine_torque_only
        0.0,                                 // p_levelling
        0.1,                                 // p_display_speed_only
        0.03,                                // p_no_lateral
    },
    {
        VehicleClass::kSaloon,                                                   // id
        "VW Passat B8, BMW 5 Series G30, Mercedes E-Class W213, Tesla Model S",  // examples
        {1450, 1850, "[TA]"},                                                    // empty_mass_kg
        {0.15, 0.30, "[TA]"},  // electric_extra_mass_fraction
        {500, 620, "[TA]"},    // payload_capacity_kg
        {2.75, 3.00, "[TA]"},  // wheelbase_m
        {1.55, 1.65, "[TA]"},  // track_m
        {0.50, 0.58, "[GIL] longitudinal engines, rear-wheel drive"},  // front_weight_share
        {0.50, 0.56, "[GIL]"},                                         // cg_height_m
        {0.55, 0.66, "[HUCHO]"},                                       // drag_area_m2
        {0.008, 0.011, "[WONG]"},                                      // rolling_f0
        {3e-6, 6e-6, "[J2452]"},                                       // rolling_f2_s2_per_m2
        {1.0, 3.0, "[WONG]"},                          // driveline_viscous_n_per_mps
        {0.31, 0.35, "[TA] 215/60 R16 - 245/40 R19"},  // wheel_radius_m
        {110, 250, "[TA]"},                            // power_kw
        {4.0, 5.5, "[ours]"},                          // wheel_inertia_kgm2
        {0.15, 0.30, "[ours]"},                        // engine_inertia_kgm2
        {13.5, 16.5, "[TA]"},                          // steering_ratio
        {15, 20, "[PAC]"},                             // cornering_per_load_front
        {18, 24, "[PAC]"},                             // cornering_per_load_rear
        4500,                                          // tyre_reference_load_n
        {24000, 35000, "[GIL]"},                       // rear_wheel_rate_n_per_m
        {2.5, 4.0, "[RCVD]"},                          // roll_gradient_deg_per_g
        {0.6, 1.4, "[RCVD]"},                          // pitch_gradient_deg_per_g
        {2.0, 4.0, "[CRO]"},                           // mode_first_gear_hz
        {6.0, 10.0, "[CRO]"},                          // mode_top_gear_hz
        {0.02, 0.05, "[ours]"},                        // vibration_rms_mps2
        {90, 130, "[GIL] [LIMP]"},                     // brake_full_pressure_bar
        {{T::kAutomatic, 0.6}, {T::kDualClutch, 0.15}, {T::kElectric, 0.25}},  // transmissions
        {{A::kRear, 0.4}, {A::kFront, 0.3}, {A::kAll, 0.3}},                   // driven_axles
        0.6,   // p_deflection_sensor
        0.9,   // p_brake_pressure
        0.1,   // p_engine_torque_only
        0.0,   // p_levelling
        0.05,  // p_display_speed_only
        0.03,  // p_no_lateral
    },
    {
        VehicleClass::kSuv,                               // id
        "VW Tiguan, BMW X5 G05, Audi Q7, Tesla Model Y",  // examples
        {1600, 2400, "[TA]"},                             // empty_mass_kg
        {0.10, 0.25, "[TA]"},                             // electric_extra_mass_fraction
        {500, 750, "[TA]"},                               // payload_capacity_kg
        {2.65, 3.00, "[TA]"},                             // wheelbase_m
        {1.58, 1.70, "[TA]"},                             // track_m
        {0.50, 0.57, "[GIL]"},                            // front_weight_share
        {0.62, 0.75, "[GIL]"},                            // cg_height_m
        {0.80, 1.05, "[HUCHO]"},                          // drag_area_m2
        {0.009, 0.012, "[WONG]"},                         // rolling_f0
        {4e-6, 7e-6, "[J2452]"},                          // rolling_f2_s2_per_m2
        {1.5, 4.0, "[WONG]"},                             // driveline_viscous_n_per_mps
        {0.34, 0.38, "[TA] 235/65 R17 - 275/45 R21"},     // wheel_radius_m
        {110, 300, "[TA]"},                               // power_kw
        {5.0, 7.5, "[ours]"},                             // wheel_inertia_kgm2
        {0.15, 0.35, "[ours]"},                           // engine_inertia_kgm2
        {14, 17, "[TA]"},                                 // steering_ratio
        {13, 18, "[PAC]"},                                // cornering_per_load_front
        {16, 22, "[PAC]"},                                // cornering_per_load_rear
        5500,                                             // tyre_reference_load_n
        {28000, 45000, "[GIL]"},                          // rear_wheel_rate_n_per_m
        {3.5, 6.0, "[RCVD] higher CG, softer roll"},      // roll_gradient_deg_per_g
        {0.8, 1.8, "[RCVD]"},                             // pitch_gradient_deg_per_g
        {2.0, 4.0, "[CRO]"},                              // mode_first_gear_hz
        {6.0, 10.0, "[CRO]"},                             // mode_top_gear_hz
        {0.03, 0.07, "[ours]"},                           // vibration_rms_mps2
        {90, 130, "[GIL] [LIMP]"},                        // brake_full_pressure_bar
        {{T::kAutomatic, 0.65}, {T::kDualClutch, 0.1}, {T::kElectric, 0.25}},  // transmissions
        {{A::kAll, 0.6}, {A::kFront, 0.25}, {A::kRear, 0.15}},                 // driven_axles
        0.7,   // p_deflection_sensor
        0.9,   // p_brake_pressure
        0.1,   // p_engine_torque_only
        0.3,   // p_levelling
        0.05,  // p_display_speed_only
        0.03,  // p_no_lateral
    },
    {
        VehicleClass::kVan,                                                         // id
        "Ford Transit Custom, VW Transporter T6.1, Renault Trafic, Mercedes Vito",  // examples
        {1750, 2400, "[TA]"},                                                       // empty_mass_kg
        {0.15, 0.30, "[TA]"},                                   // electric_extra_mass_fraction
        {900, 1400, "[TA]"},                                    // payload_capacity_kg
        {3.00, 3.70, "[TA]"},                                   // wheelbase_m
        {1.62, 1.75, "[TA]"},                                   // track_m
        {0.55, 0.63, "[GIL] empty van, engine ahead"},          // front_weight_share
        {0.75, 0.90, "[GIL]"},                                  // cg_height_m
        {1.10, 1.40, "[HUCHO]"},                                // drag_area_m2
        {0.008, 0.011, "[WONG] C-type tyres"},                  // rolling_f0
        {3e-6, 6e-6, "[J2452]"},                                // rolling_f2_s2_per_m2
        {1.5, 4.0, "[WONG]"},                                   // driveline_viscous_n_per_mps
        {0.33, 0.36, "[TA] 215/65 R16C - 235/65 R16C"},         // wheel_radius_m
        {80, 150, "[TA]"},                                      // power_kw
        {5.0, 7.0, "[ours]"},                                   // wheel_inertia_kgm2
        {0.20, 0.35, "[ours] diesel with dual-mass flywheel"},  // engine_inertia_kgm2
        {15, 19, "[TA]"},                                       // steering_ratio
        {11, 16, "[PAC] C-type tyres"},                         // cornering_per_load_front
        {13, 18, "[PAC]"},                                      // cornering_per_load_rear
        6500,                                                   // tyre_reference_load_n
        {45000, 90000, "[GIL] load-carrying rear springs"},     // rear_wheel_rate_n_per_m
        {4.0, 7.0, "[RCVD]"},                                   // roll_gradient_deg_per_g
        {0.8, 2.0, "[RCVD]"},                                   // pitch_gradient_deg_per_g
        {2.0, 4.0, "[CRO]"},                                    // mode_first_gear_hz
        {6.0, 10.0, "[CRO]"},                                   // mode_top_gear_hz
        {0.04, 0.09, "[ours] stiffer springs"},                 // vibration_rms_mps2
        {100, 140, "[GIL] [LIMP]"},                             // brake_full_pressure_bar
        {{T::kManual, 0.5}, {T::kAutomatic, 0.4}, {T::kElectric, 0.1}},  // transmissions
        {{A::kFront, 0.5}, {A::kRear, 0.4}, {A::kAll, 0.1}},             // driven_axles
        0.4,                                                             // p_deflection_sensor
        0.85,                                                            // p_brake_pressure
        0.2,                                                             // p_engine_torque_only
        0.15,                                                            // p_levelling
        0.1,                                                             // p_display_speed_only
        0.03,                                                            // p_no_lateral
    },
    {
        VehicleClass::kPickup,                                     // id
        "Toyota Hilux AN120, Ford Ranger, Ford F-150, VW Amarok",  // examples
        {1900, 2500, "[TA]"},                                      // empty_mass_kg
        {0.2, 0.3, "[TA]"},                                        // electric_extra_mass_fraction
        {700, 1100, "[TA]"},                                       // payload_capacity_kg
        {3.00, 3.70, "[TA]"},                                      // wheelbase_m
        {1.55, 1.70, "[TA]"},                                      // track_m
        {0.55, 0.61, "[GIL] empty bed"},                           // front_weight_share
        {0.72, 0.85, "[GIL]"},                                     // cg_height_m
        {1.00, 1.25, "[HUCHO]"},                                   // drag_area_m2
        {0.009, 0.013, "[WONG] light-truck tyres"},                // rolling_f0
        {4e-6, 7e-6, "[J2452]"},                                   // rolling_f2_s2_per_m2
        {2.0, 6.0, "[WONG] solid rear axle, transfer case"},       // driveline_viscous_n_per_mps
        {0.37, 0.41, "[TA] 265/65 R17 - 275/60 R20"},              // wheel_radius_m
        {110, 300, "[TA]"},                                        // power_kw
        {6.0, 9.0, "[ours]"},                                      // wheel_inertia_kgm2
        {0.20, 0.40, "[ours]"},                                    // engine_inertia_kgm2
        {16, 20, "[TA]"},                                          // steering_ratio
        {11, 16, "[PAC] LT tyres"},                                // cornering_per_load_front
        {13, 18, "[PAC]"},                                         // cornering_per_load_rear
        6500,                                                      // tyre_reference_load_n
        {60000, 120000, "[GIL] leaf springs"},                     // rear_wheel_rate_n_per_m
        {4.0, 7.0, "[RCVD]"},                                      // roll_gradient_deg_per_g
        {0.8, 2.0, "[RCVD]"},                                      // pitch_gradient_deg_per_g
        {2.0, 4.0, "[CRO]"},                                       // mode_first_gear_hz
        {6.0, 10.0, "[CRO]"},                                      // mode_top_gear_hz
        {0.04, 0.10, "[ours] leaf springs, solid axle"},           // vibration_rms_mps2
        {100, 140, "[GIL] [LIMP]"},                                // brake_full_pressure_bar
        {{T::kAutomatic, 0.7}, {T::kManual, 0.3}},                 // transmissions
        {{A::kRear, 0.4}, {A::kAll, 0.6}},                         // driven_axles
        0.35,                                                      // p_deflection_sensor
        0.85,                                                      // p_brake_pressure
        0.25,                                                      // p_engine_torque_only
        0.0,                                                       // p_levelling
        0.1,                                                       // p_display_speed_only
        0.03,                                                      // p_no_lateral
    },
    {
        VehicleClass::kHeavyTruck,                                                      // id
        "rigid three-axle 26 t: Mercedes Actros/Arocs 2630, Volvo FM 6x2, MAN TGS 26",  // examples
        {9000, 12500, "[TA]"},                                       // empty_mass_kg
        {0.0, 0.0, "[ours] no electric trucks in this population"},  // electric_extra_mass_fraction
        {13500, 17000, "[TA] 26 t GVW"},                             // payload_capacity_kg
        {4.5, 6.0, "[TA] front axle to the tandem's centre"},        // wheelbase_m
        {2.00, 2.10, "[TA]"},                                        // track_m
        {0.50, 0.60, "[TA] empty chassis with body"},                // front_weight_share
        {1.00, 1.30, "[WONG]"},                                      // cg_height_m
        {5.5, 7.5, "[HUCHO] [WONG]"},                                // drag_area_m2
        {0.005, 0.007, "[WONG] truck tyres"},                        // rolling_f0
        {1e-6, 3e-6, "[J2452]"},                                     // rolling_f2_s2_per_m2
        {150, 310,
         "[WONG] ~9.5 kN at 31 m/s observed by a partner team"},     // driveline_viscous_n_per_mps
        {0.49, 0.53, "[TA] 315/80 R22.5"},                           // wheel_radius_m
        {250, 400, "[TA]"},                                          // power_kw
        {100, 160, "[ours] ten wheels with drums or discs, axles"},  // wheel_inertia_kgm2
        {2.5, 4.0, "[ours] 11-13 l engine with flywheel"},           // engine_inertia_kgm2
        {18, 24, "[TA]"},                                            // steering_ratio
        {6, 9, "[PAC] truck tyres"},                                 // cornering_per_load_front
        {7, 10, "[PAC]"},                                            // cornering_per_load_rear
        25000,                                                       // tyre_reference_load_n
        {400000, 800000, "[WONG] leaf-sprung tandem, per wheel"},    // rear_wheel_rate_n_per_m
        {4.0, 8.0, "[ours] high CG, stiff springs"},                 // roll_gradient_deg_per_g
        {0.5, 1.2, "[ours] long wheelbase"},                         // pitch_gradient_deg_per_g
        {1.2, 2.5,
         "[ours] heavier reflected inertia than cars ([CRO] scaled)"},  // mode_first_gear_hz
        {3.5, 6.0, "[ours]"},                                           // mode_top_gear_hz
        {0.06, 0.15, "[ours] cab-mounted ESC unit"},                    // vibration_rms_mps2
        {6, 8, "[LIMP] air brakes"},                                    // brake_full_pressure_bar
        {{T::kAutomatedManual, 0.85}, {T::kAutomatic, 0.15}},           // transmissions
        {{A::kRear, 1.0}},                                              // driven_axles
        0.5,                                                            // p_deflection_sensor
        0.9,                                                            // p_brake_pressure
        0.3,                                                            // p_engine_torque_only
        0.8,                                                            // p_levelling
        0.05,                                                           // p_display_speed_only
        0.03,                                                           // p_no_lateral
    },
};

const CommonRanges kCommonRanges = {
    {0.010, 0.040, "[CRO] actuation and ECU computation"},            // driveline_lag_s
    {0.05, 0.30, "[CRO] lightly damped"},                             // mode_damping_ratio
    {0.06, 0.20, "[ours] turbocharged engines; electric 0.02-0.05"},  // torque_time_constant_s
    {1.8, 2.3, "[CRO]"},                                              // tc_stall_torque_ratio
    {0.82, 0.90, "[CRO]"},                                            // tc_coupling_speed_ratio
    {5.0, 12.0, "[ours] lock-up from 2nd gear"},                      // tc_lockup_speed_mps
    {-0.25, 0.25, "[ours] the TCU's converter map against the real one"},  // tc_model_error
    {0.03, 0.05, "[ours] creep moves a car on the flat"},                  // creep_force_per_weight
    {-0.4, 0.4, "[ours] drag torque maps are the least accurate part"},    // drag_report_error
    {1000, 3000, "[ours] belt-driven A/C compressor (trucks x2)"},         // accessory_power_w
    {0.12, 0.25, "[TA] one-pedal and blended regen limits"},               // regen_max_decel_g
    {20, 40, "[ESC]"},                                                     // imu_filter_cutoff_hz
    {-0.08, 0.08, "[ESC] zero-g offset after mounting"},                   // imu_bias_mps2
    {2e-4, 1e-3, "[ESC] temperature drift as a random walk"},         // imu_drift_mps2_per_sqrt_s
    {0.01, 0.03, "[ESC] per 100 Hz sample"},                          // imu_noise_std_mps2
    {8, 25, "[ours] wheel hop and body-mount modes"},                 // imu_vibration_frequency_hz
    {-1.0, 1.0, "[ours] mounting tolerance"},                         // imu_misalignment_deg
    {-0.3, 0.5, "[ours] ESC unit under the seats or in the tunnel"},  // imu_lever_forward_m
    {-0.2, 0.2, "[ours]"},                                            // imu_lever_left_m
    {-0.015, 0.015,
     "[ours] tyre wear, pressure, load vs the ESC's radius"},    // speed_radius_error_fraction
    {0.01, 0.04, "[R39]"},                                       // display_overread_fraction
    {0.0, 0.3, "[ours] sensor zero offset"},                     // brake_pressure_offset_bar
    {0.15, 0.35, "[LIMP]"},                                      // brake_fade_max_fraction
    {-0.02, 0.04, "[TA] fuel level, options, tolerances"},       // empty_mass_deviation_fraction
    {0.0, 0.040, "[ours] sensor filtering and gateway delays"},  // ecu_latency_s
};

}  // namespace

const std::vector<ClassDefinition>& vehicle_classes() { return kClassTable; }

const ClassDefinition& class_definition(VehicleClass c) {
  return kClassTable[static_cast<std::size_t>(c)];
}

const CommonRanges& common_ranges() { return kCommonRanges; }

}  // namespace vmass::sim
