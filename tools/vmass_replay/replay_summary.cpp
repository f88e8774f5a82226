#include "replay_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "vmass/csv/csv.hpp"

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

std::string_view describe_prior(StatusReason prior_reason) {
  switch (prior_reason) {
    case StatusReason::kStaticInitialised:
      return "static prior, eq. 3";
    case StatusReason::kLoadChanged:
      return "static prior after a load change, eq. 3";
    case StatusReason::kNoStaticPrior:
      return "no-static prior: driving began before any standstill";
    case StatusReason::kRestored:
      return "prior restored from a saved state";
    case StatusReason::kNoLoadSensor:
      return "no load sensor: the empty mass plus half the payload capacity";
    default:
      return "no prior";
  }
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
  check_tolerances(e);
  if (truth_ && e.pairs_used > 0) {
    const double truth = truth_->mass_at(e.time_us);
    ++dynamic_ticks_;
    if (e.ci_low_kg <= truth && truth <= e.ci_high_kg) ++covered_ticks_;
  }
}

void ReplaySummary::finish(const Estimate& flushed) {
  if (!has_last_ || !flushed.has_mass()) return;
  last_ = flushed;
  check_tolerances(flushed);
}

void ReplaySummary::check_tolerances(const Estimate& e) {
  if (!truth_) return;
  const double truth = truth_->mass_at(e.time_us);
  const double rel = std::abs(e.mass_kg - truth) / truth;
  for (int i = 0; i < 3; ++i) {
    if (rel > kTolerances[i]) last_outside_[i] = e.time_us;
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
  for (const BlockCounters& c : last_.blocks) r.pairs_accepted += c.accepted;
  if (!truth_ || !any_mass_) return r;
  r.true_mass_kg = truth_->mass_at(last_.time_us);
  r.error_percent = 100.0 * (last_.mass_kg - *r.true_mass_kg) / *r.true_mass_kg;
  if (dynamic_ticks_ > 0) {
    r.coverage = static_cast<double>(covered_ticks_) / static_cast<double>(dynamic_ticks_);
  }
  if (last_.pairs_used == 0) return r;  // the prior only: no "within" claim
  std::optional<double>* outs[3] = {&r.time_within_5_s, &r.time_within_2_s, &r.time_within_1_s};
  for (int i = 0; i < 3; ++i) {
    if (!last_outside_[i]) {
      *outs[i] = to_seconds(first_mass_us_ - first_us_);
    } else if (*last_outside_[i] < last_.time_us) {
      *outs[i] = to_seconds(*last_outside_[i] - first_us_);
    }
  }
  return r;
}

namespace {

const char* const kBlockLabels[kBlockCount] = {"longitudinal         ", "lateral              "};
const char* const kBlockKeys[kBlockCount] = {"longitudinal", "lateral"};

std::string within_line(const ReplaySummary::Result& r, const std::optional<double>& t) {
  if (r.final_estimate.pairs_used == 0) return "n/a (no pair used: the estimate is the prior)";
  return opt_seconds(t);
}

void truth_rows(const ReplaySummary::Result& r, std::ostringstream& out) {
  out << "true mass            " << fixed(*r.true_mass_kg, 1) << " kg\n";
  out << "error                " << fixed(*r.error_percent, 3) << " %\n";
  out << "within 5% from       " << within_line(r, r.time_within_5_s) << "\n";
  out << "within 2% from       " << within_line(r, r.time_within_2_s) << "\n";
  out << "within 1% from       " << within_line(r, r.time_within_1_s) << "\n";
  out << "interval coverage    "
      << (r.coverage ? fixed(100.0 * *r.coverage, 1) + "% of ticks" : std::string("n/a")) << "\n";
}

}  // namespace

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
  out << "final mass           " << fixed(e.mass_kg, 1) << " kg"
      << (e.pairs_used == 0 ? " (the prior: no pair used)" : "") << "\n";
  out << "95% interval         [" << fixed(e.ci_low_kg, 1) << ", " << fixed(e.ci_high_kg, 1)
      << "] kg (std " << fixed(e.mass_std_kg, 1) << " kg)\n";
  out << "mu                   " << fixed(e.mu_n, 1) << " N\n";
  out << "prior                " << fixed(e.initial_mass_kg, 1) << " kg ("
      << describe_prior(e.prior_reason) << ")\n";
  if (r.reinitialisations > 0) out << "re-initialisations   " << r.reinitialisations << "\n";
  out << "status               " << status_name(e.status) << " (" << e.describe_reason() << ")\n";
  out << "pairs used           " << e.pairs_used << " (in the estimate)\n";
  out << "pairs accepted       " << r.pairs_accepted << " (by the supervisor)\n";
  for (int b = 0; b < kBlockCount; ++b) {
    const BlockCounters& c = e.blocks[static_cast<std::size_t>(b)];
    out << kBlockLabels[b] << "availability " << fixed(100.0 * c.availability(), 1) << "% ("
        << c.accepted << " accepted, " << c.rejected_innovation << " innovation-rejected of "
        << c.candidates << " candidates)\n";
  }
  if (r.true_mass_kg) truth_rows(r, out);
  return out.str();
}

std::string ReplaySummary::json(const std::string& estimator_name) const {
  const Result r = result();
  const Estimate& e = r.final_estimate;
  auto mass = [&](double v) { return r.has_estimate ? fixed(v, 3) : std::string("null"); };
  std::ostringstream out;
  out << "{\"estimator\": \"" << estimator_name << "\", \"duration_s\": " << fixed(r.duration_s, 3)
      << ", \"ticks\": " << r.ticks << ", \"has_estimate\": " << (r.has_estimate ? "true" : "false")
      << ", \"mass_kg\": " << mass(e.mass_kg) << ", \"ci_low_kg\": " << mass(e.ci_low_kg)
      << ", \"ci_high_kg\": " << mass(e.ci_high_kg) << ", \"mass_std_kg\": " << mass(e.mass_std_kg)
      << ", \"mu_n\": " << mass(e.mu_n) << ", \"initial_mass_kg\": " << mass(e.initial_mass_kg)
      << ", \"prior\": \"" << reason_name(e.prior_reason)
      << "\", \"reinitialisations\": " << r.reinitialisations << ", \"status\": \""
      << status_name(e.status) << "\", \"reason\": \"" << e.describe_reason()
      << "\", \"pairs_used\": " << e.pairs_used << ", \"pairs_accepted\": " << r.pairs_accepted;
  for (int b = 0; b < kBlockCount; ++b) {
    const BlockCounters& c = e.blocks[static_cast<std::size_t>(b)];
    out << ", \"" << kBlockKeys[b] << "_availability\": " << fixed(c.availability(), 5) << ", \""
        << kBlockKeys[b] << "\": {\"ticks\": " << c.ticks << ", \"candidates\": " << c.candidates
        << ", \"accepted\": " << c.accepted
        << ", \"rejected_innovation\": " << c.rejected_innovation << "}";
  }
  out << ", \"true_mass_kg\": " << opt_json(r.true_mass_kg, 3)
      << ", \"error_percent\": " << opt_json(r.error_percent, 5)
      << ", \"time_within_5_s\": " << opt_json(r.time_within_5_s, 3)
      << ", \"time_within_2_s\": " << opt_json(r.time_within_2_s, 3)
      << ", \"time_within_1_s\": " << opt_json(r.time_within_1_s, 3)
      << ", \"coverage\": " << opt_json(r.coverage, 5) << "}";
  return out.str();
}

}  // namespace vmass
