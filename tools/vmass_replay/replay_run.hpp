// One recording played through the tick grid (runtime::TickDriver, runtime::TickStep) into a
// ReplaySummary and, when given, an estimate CSV: the loop both of vmass-replay's modes (one
// input, many logs) run, exactly as vmassd --speed max does.
// Not thread-safe; one run per thread (many logs: one per worker).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "known_mass_option.hpp"

#include "vmass/csv/estimate_csv.hpp"
#include "vmass/runtime/input_source.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/runtime/tick_step.hpp"
#include "vmass/scoring/replay_summary.hpp"

namespace vmass {

/// Plays the whole recording: every tick's estimate into *summary and, when writer is not
/// null, the CSV; each known mass declared at the first tick at or after its time (sorted).
/// Returns "" on success, else why the truth was refused (checked at tick 0; nothing is
/// summarised or written after a refusal).
std::string play_recording(runtime::InputSource& source, runtime::TickStep& step,
                           const std::optional<scoring::Truth>& truth,
                           const std::vector<KnownMassEvent>& known_masses,
                           scoring::ReplaySummary* summary, EstimateCsvWriter* writer,
                           runtime::TickRun* run);

}  // namespace vmass
