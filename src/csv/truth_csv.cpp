#include "vmass/csv/truth_csv.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "vmass/csv/csv.hpp"
#include "vmass/io/line_reader.hpp"
#include "vmass/io/regular_file.hpp"

namespace vmass {
namespace {

std::string seconds_text(TimeUs t) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f", to_seconds(t));
  return buf;
}

}  // namespace

Truth::Truth(std::vector<TimeUs> times, std::vector<double> masses)
    : times_(std::move(times)), masses_kg_(std::move(masses)) {}

std::optional<Truth> Truth::load(const std::string& path, std::string* error) {
  const io::FileText file = io::read_regular_file(path, io::kMaxTableBytes, "truth file");
  if (!file.ok()) {
    *error = file.error;
    return std::nullopt;
  }
  std::istringstream in(file.text);
  io::LineReader lines(in);
  std::string line;
  lines.next(&line);
  const auto header = split_csv_line(line);
  if (header.size() < 2 || header[0] != "time_s" || header[1] != "mass_kg") {
    *error = path + ":1: expected a header starting with time_s,mass_kg";
    return std::nullopt;
  }
  std::vector<TimeUs> times;
  std::vector<double> masses;
  while (lines.next(&line)) {
    if (line.empty()) continue;
    const auto cells = split_csv_line(line);
    double t = 0.0, m = 0.0;
    const std::string at = path + ":" + std::to_string(lines.line_number()) + ": ";
    if (cells.size() < 2 || !parse_csv_number(cells[0], &t) || !parse_csv_number(cells[1], &m) ||
        !(std::abs(t) <= 1e10) || !std::isfinite(m)) {
      *error = at + "expected time_s,mass_kg numbers (|time_s| <= 1e10 s)";
      return std::nullopt;
    }
    if (!times.empty() && from_seconds(t) < times.back()) {
      *error = at + "time_s goes back";
      return std::nullopt;
    }
    times.push_back(from_seconds(t));
    masses.push_back(m);
  }
  if (times.empty()) {
    *error = path + ": no rows";
    return std::nullopt;
  }
  return Truth(std::move(times), std::move(masses));
}

double Truth::mass_at(TimeUs t) const {
  auto it = std::upper_bound(times_.begin(), times_.end(), t);
  if (it == times_.begin()) return masses_kg_.front();
  return masses_kg_[static_cast<std::size_t>(std::distance(times_.begin(), it) - 1)];
}

std::string Truth::check_time_base(TimeUs first_tick_us, TimeUs tick_period_us) const {
  if (first_tick_us >= first_time_us() - tick_period_us &&
      first_tick_us <= last_time_us() + tick_period_us) {
    return "";
  }
  return "its times (" + seconds_text(first_time_us()) + " to " + seconds_text(last_time_us()) +
         " s) do not contain the input's first tick (" + seconds_text(first_tick_us) +
         " s): another time base (a log with epoch times needs a truth in the same times)";
}

}  // namespace vmass
