#include "vmass/replay/replay_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "vmass/replay/csv.hpp"

namespace vmass {
namespace {
constexpr double kTolerances[3] = {0.05, 0.02, 0.01};

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}
std::string opt_seconds(const std::optional<double>& v) {
  return v ? fixed(*v, 2) + " s" : std::string("never");
}
std::string opt_json(const std::optional<double>& v, int digits) {
  return v ? fixed(*v, digits) : std::string("null");
}
}  // namespace

Truth::Truth(std::vector<TimeUs> times, std::vector<double> masses)
    : times_(std::move(times)), masses_kg_(std::move(masses)) {}

std::optional<Truth> Truth::load(const std::string& path, std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = path + ": cannot open the truth file";
    return std::nullopt;
  }
  std::string line;
  std::getline(in, line);
  const auto header = split_csv_line(line);
  if (header.size() < 2 || header[0] != "time_s" || header[1] != "mass_kg") {
    *error = path + ":1: expected a header starting with time_s,mass_kg";
    return std::nullopt;
  }
  std::vector<TimeUs> times;
  std::vector<double> masses;
  long number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    const auto cells = split_csv_line(line);
    double t = 0.0, m = 0.0;
    if (cells.size() < 2 || !parse_csv_number(cells[0], &t) || !parse_csv_number(cells[1], &m)) {
      *error = path + ":" + std::to_string(number) + ": expected time_s,mass_kg numbers";
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

void ReplaySummary::add(const Estimate& e) {
  if (!started_) {
    started_ = true;
    first_us_ = e.time_us;
  }
  ++ticks_;
  if (has_last_ && e.initial_mass_kg != last_.initial_mass_kg && last_.has_mass()) {
    ++reinitialisations_;  // a new prior: load change
  }
  last_ = e;
  has_last_ = true;
  if (!e.has_mass()) return;
  if (!any_mass_) {
    any_mass_ = true;
    first_mass_us_ = e.time_us;
  }
  if (!truth_) return;
  const double truth = truth_->mass_at(e.time_us);
  const double rel = std::abs(e.mass_kg - truth) / truth;
  for (int i = 0; i < 3; ++i) {
    if (rel > kTolerances[i]) last_outside_[i] = e.time_us;
  }
  if (e.pairs_used > 0) {
    ++dynamic_ticks_;
    if (e.ci_low_kg <= truth && truth <= e.ci_high_kg) ++covered_ticks_;
  }
}

ReplaySummary::Result ReplaySummary::result() const {
  Result r;
  r.ticks = ticks_;
  r.reinitialisations = reinitialisations_;
  if (!has_last_) return r;
  r.duration_s = to_seconds(last_.time_us - first_us_);
  r.final_estimate = last_;
  r.has_estimate = any_mass_;
  if (!truth_ || !any_mass_) return r;
  r.true_mass_kg = truth_->mass_at(last_.time_us);
  r.error_percent = 100.0 * (last_.mass_kg - *r.true_mass_kg) / *r.true_mass_kg;
  std::optional<double>* outs[3] = {&r.time_within_5_s, &r.time_within_2_s, &r.time_within_1_s};
  for (int i = 0; i < 3; ++i) {
    if (!last_outside_[i]) {
      *outs[i] = to_seconds(first_mass_us_ - first_us_);
    } else if (*last_outside_[i] < last_.time_us) {
      *outs[i] = to_seconds(*last_outside_[i] - first_us_);
    }
  }
  if (dynamic_ticks_ > 0) {
    r.coverage = static_cast<double>(covered_ticks_) / static_cast<double>(dynamic_ticks_);
  }
  return r;
}

std::string ReplaySummary::table(const std::string& estimator_name) const {
  const Result r = result();
  std::ostringstream out;
  const Estimate& e = r.final_estimate;
  out << "estimator            " << estimator_name << "\n";
  out << "duration             " << fixed(r.duration_s, 2) << " s, " << r.ticks << " ticks\n";
  if (!r.has_estimate) {
    out << "final mass           none (status " << status_name(e.status) << ", "
        << e.describe_reason() << ")\n";
    return out.str();
  }
  out << "final mass           " << fixed(e.mass_kg, 1) << " kg\n";
  out << "95% interval         [" << fixed(e.ci_low_kg, 1) << ", " << fixed(e.ci_high_kg, 1)
      << "] kg (std " << fixed(e.mass_std_kg, 1) << " kg)\n";
  out << "mu                   " << fixed(e.mu_n, 1) << " N\n";
  out << "initial (static)     " << fixed(e.initial_mass_kg, 1) << " kg\n";
  out << "status               " << status_name(e.status) << " (" << e.describe_reason() << ")\n";
  out << "pairs used           " << e.pairs_used << "\n";
  for (int b = 0; b < kBlockCount; ++b) {
    const BlockCounters& c = e.blocks[static_cast<std::size_t>(b)];
    out << (b == 0 ? "longitudinal         " : "lateral              ") << "availability "
        << fixed(100.0 * c.availability(), 1) << "% (" << c.accepted << " accepted, "
        << c.rejected_innovation << " innovation-rejected of " << c.candidates
        << " candidates)\n";
  }
  if (r.true_mass_kg) {
    out << "true mass            " << fixed(*r.true_mass_kg, 1) << " kg\n";
    out << "error                " << fixed(*r.error_percent, 3) << " %\n";
    out << "within 5% from       " << opt_seconds(r.time_within_5_s) << "\n";
    out << "within 2% from       " << opt_seconds(r.time_within_2_s) << "\n";
    out << "within 1% from       " << opt_seconds(r.time_within_1_s) << "\n";
    out << "interval coverage    "
        << (r.coverage ? fixed(100.0 * *r.coverage, 1) + "% of ticks" : std::string("n/a"))
        << "\n";
  }
  return out.str();
}

std::string ReplaySummary::json(const std::string& estimator_name) const {
  const Result r = result();
  const Estimate& e = r.final_estimate;
  std::ostringstream out;
  out << "{\"estimator\": \"" << estimator_name << "\", \"duration_s\": " << fixed(r.duration_s, 3)
      << ", \"has_estimate\": " << (r.has_estimate ? "true" : "false")
      << ", \"mass_kg\": " << fixed(e.mass_kg, 3) << ", \"ci_low_kg\": " << fixed(e.ci_low_kg, 3)
      << ", \"ci_high_kg\": " << fixed(e.ci_high_kg, 3) << ", \"mu_n\": " << fixed(e.mu_n, 3)
      << ", \"status\": \"" << status_name(e.status) << "\", \"pairs_used\": " << e.pairs_used
      << ", \"longitudinal_availability\": " << fixed(e.blocks[0].availability(), 5)
      << ", \"lateral_availability\": " << fixed(e.blocks[1].availability(), 5)
      << ", \"true_mass_kg\": " << opt_json(r.true_mass_kg, 3)
      << ", \"error_percent\": " << opt_json(r.error_percent, 5)
      << ", \"time_within_5_s\": " << opt_json(r.time_within_5_s, 3)
      << ", \"time_within_2_s\": " << opt_json(r.time_within_2_s, 3)
      << ", \"time_within_1_s\": " << opt_json(r.time_within_1_s, 3)
      << ", \"coverage\": " << opt_json(r.coverage, 5) << "}";
  return out.str();
}

}  // namespace vmass
