// One recording played through the tick grid (runtime::TickDriver, runtime::TickStep) into a
// ReplaySummary and each tick's estimate (an estimate CSV, or any sink): the loop vmass-replay's
// two modes (one input, many logs) and the Python bindings run, exactly as vmassd --speed max
// does.
// Not thread-safe; one run per thread (many logs: one per worker).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "vmass/csv/estimate_csv.hpp"
#include "vmass/replay/known_mass_option.hpp"
#include "vmass/runtime/input_source.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/runtime/tick_step.hpp"
#include "vmass/scoring/replay_summary.hpp"

namespace vmass {

/// Where each tick's estimate goes besides the summary (null: nowhere).
using EstimateSink = std::function<void(const Estimate&)>;

/// Plays the whole recording: every tick's estimate into *summary and `sink`; each known mass
/// declared at the first tick at or after its time (sorted). Returns "" on success, else why
/// the truth was refused (checked at tick 0; nothing is summarised or sunk after a refusal).
std::string play_recording(runtime::InputSource& source, runtime::TickStep& step,
                           const std::optional<scoring::Truth>& truth,
                           const std::vector<KnownMassEvent>& known_masses,
                           scoring::ReplaySummary* summary, const EstimateSink& sink,
                           runtime::TickRun* run);

/// The same, each estimate written to the CSV when writer is not null.
std::string play_recording(runtime::InputSource& source, runtime::TickStep& step,
                           const std::optional<scoring::Truth>& truth,
                           const std::vector<KnownMassEvent>& known_masses,
                           scoring::ReplaySummary* summary, EstimateCsvWriter* writer,
                           runtime::TickRun* run);

}  // namespace vmass
