// The report vmass-monitor prints: what vmassd last published on LCM, laid out for an
// 80-column terminal. Each line is a label column (10 characters) and items separated by three
// blanks; items that do not fit continue on the next line under the first item, and an item
// longer than a whole line (a long input path) is shortened in its middle with "...". Text
// (vmassd's answer to the last command, why no pair came) wraps at its words.
//
// Pure: no LCM traffic, no terminal; thread-safe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <vmass/mass_estimate_t.hpp>
#include <vmass/status_t.hpp>

#include "verdict_history.hpp"

namespace vmass::monitor {

constexpr std::size_t kReportWidth = 80;

/// `label` padded to the label column, then the items wrapped at `width` columns, `gap`
/// between two items on a line (" ": words of a text).
std::string wrap_items(std::string_view label, const std::vector<std::string>& items,
                       std::size_t width = kReportWidth, std::string_view gap = "   ");

/// How long vmassd has been silent, for the report's warning line.
struct Silence {
  double estimate_s = 0.0;  ///< since the last estimate (since the monitor started, before one)
  double status_s = -1.0;   ///< since the last status; negative: none received
  double limit_s = 0.0;     ///< estimates silent for longer: the warning (0: never)
};

/// "no estimate for 12 s: is vmassd running?" (with the last status's age), or "" while the
/// estimates arrive.
std::string silence_message(const Silence& silence);

/// What the monitor gathered beyond the last message of each channel.
struct ReportContext {
  NoPairStretch no_pair;       ///< the longitudinal block's latest stretch without a pair
  std::int64_t now_utime = 0;  ///< CLOCK_REALTIME now, us, for the last command's age (0: none)
};

/// "no longitudinal pair in 180 s: 17,800 ticks small_delta_force, 200 settling" (the three
/// verdicts with the most ticks, then the rest together), as phrases that wrap as a whole (with
/// the gap " "); none when span_s is 0.
std::vector<std::string> no_pair_items(const NoPairStretch& stretch);

/// The whole report; null messages print as "(no ... received)". When the estimates have been
/// silent for longer than silence.limit_s, a warning line under the first says so. Below the
/// estimate: why no longitudinal pair came lately (context.no_pair), what vmassd learnt about the
/// car and its answer to the last command (vmass-ctl), with its age.
std::string monitor_report(const std::string& url, double estimate_hz, double status_hz,
                           const vmass::mass_estimate_t* estimate, const vmass::status_t* status,
                           const Silence& silence = {}, const ReportContext& context = {});

}  // namespace vmass::monitor
