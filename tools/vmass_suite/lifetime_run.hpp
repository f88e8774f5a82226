// The accuracy suite's lifetime mode: one population vehicle driven drive after drive
// (vmass/sim/lifetime.hpp: the load changed while parked before at least half of the drives,
// a day between drives). Every drive goes through vmass twice, on the same frames:
//   lifetime  restored from the state file the last drive saved, as vmassd restores it at its
//             start under systemd (service::restore_pipeline_state: the same file, the same
//             checks), and saved there at its end with the open batch flushed, as at vmassd's
//             stop (tests/suite/lifetime_daemon_test.sh checks that vmassd --replay writes the
//             same file);
//   fresh     a new pipeline, as every other figure of the suite.
// For each kind of knowledge, and on a vehicle with a deflection sensor also without it (the
// same bus without the level message, the config without a suspension section); with
// known_mass_drives each of those also with the true mass declared at the start of those drives
// (its lifetime rows only: its fresh drives are the variant's without).
//
// Thread-safe for distinct work directories.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vmass/sim/datasheet_config.hpp"
#include "vmass/sim/lifetime.hpp"
#include "vmass/sim/realism.hpp"

namespace vmass::suite {

struct LifetimeSpec {
  std::string vehicle_id;
  std::uint64_t life = 1;  ///< which life (other loads, other drives)
  int drives = 10;
  /// Empty: sim::plan_lifetime(vehicle, drives, life); else these drives (a test's own life).
  std::vector<sim::LifetimeDrive> plan;
  std::vector<sim::Knowledge> knowledge = {sim::Knowledge::kKnownScale,
                                           sim::Knowledge::kDatasheetScale};
  std::vector<std::string> estimators = {"bayes"};  ///< rls and/or bayes
  std::string estimator_yaml;                       ///< appended to every config (experiments)
  sim::Realism realism = sim::Realism::all();
  std::string realism_label = "all";
  /// "": nothing kept; else each variant's drives as candump logs, its config and DBC, and the
  /// state file after each drive, in DIR/<vehicle>_<knowledge>_<sensor>_<estimator>/.
  std::string keep_dir;
  /// "": no series; else per-tick CSVs (10 Hz) of every drive, both modes, in DIR.
  std::string series_dir;
  /// Non-empty: every variant is also carried with a known mass declared (Pipeline::
  /// declare_known_mass, a weighbridge ticket) at the start of these drives (1-based): the true
  /// mass off by an error drawn from known_mass_std_fraction, the std it is declared with.
  std::vector<int> known_mass_drives;
  /// Heavy trucks: these drives instead (empty: known_mass_drives). Issue 30 asks a truck for two
  /// known masses at different loads (every even drive's load is changed), a car for one.
  std::vector<int> truck_known_mass_drives;
  /// > 1: new tyres before this drive (sim::plan_lifetime), the config's radius unchanged.
  int tyre_change_drive = 0;
  /// With tyre_change_drive: the workshop declares the new tyres (Pipeline::tyres_changed(), as
  /// `vmass-ctl tyres-changed`) at the start of that drive.
  bool tyre_change_declared = false;
  /// > 1: a tractor couples another trailer before this drive (sim::plan_lifetime), the
  /// config's drag area and rolling coefficient unchanged.
  int trailer_change_drive = 0;
  /// The declared known mass's relative std (a weighbridge's, or a datasheet's "empty").
  double known_mass_std_fraction = 0.005;
};

struct LifetimeResult {
  std::string error;       ///< the life itself failed (a bug)
  std::string json_lines;  ///< one line per (drive, variant, estimator, mode)
};

LifetimeResult run_lifetime(const LifetimeSpec& spec, const std::string& work_dir);

}  // namespace vmass::suite
