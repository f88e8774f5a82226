#include "vmass/scoring/replay_summary_text.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "vmass/json/json.hpp"

namespace vmass::scoring {
namespace {

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}
// "+0.028", "-512": the sign always shown (a -0.0 shows as +0).
std::string signed_fixed(double v, int digits) {
  return (v >= 0.0 ? "+" : "") + fixed(v + 0.0, digits);
}
std::string opt_seconds(const std::optional<double>& v) {
  return v ? fixed(*v, 2) + " s" : std::string("never");
}

const char* const kBlockLabels[kBlockCount] = {"longitudinal         ", "lateral              "};
const char* const kBlockKeys[kBlockCount] = {"longitudinal", "lateral"};
const char* const kWithinLabels[kToleranceCount] = {
    "within 5% from       ", "within 2% from       ", "within 1% from       "};

std::string within_line(const ReplaySummary::Result& r, const std::optional<double>& t) {
  if (r.final_estimate.pairs_used == 0) return "n/a (no pair used: the estimate is the prior)";
  return opt_seconds(t);
}

void truth_rows(const ReplaySummary::Result& r, std::ostringstream& out) {
  out << "true mass            " << fixed(*r.true_mass_kg, 1) << " kg\n";
  out << "error                " << fixed(*r.error_percent, 3) << " %\n";
  for (std::size_t i = 0; i < kToleranceCount; ++i) {
    out << kWithinLabels[i] << within_line(r, r.time_within_since_first_tick_s[i]) << "\n";
  }
  const std::optional<double>& coverage = r.coverage_of_dynamic_ticks;
  out << "interval coverage    "
      << (coverage ? fixed(100.0 * *coverage, 1) + "% of ticks" : std::string("n/a")) << "\n";
}

void learnt_rows(const ReplaySummary::Result::Learnt& l, std::ostringstream& out) {
  if (l.known_masses > 0) out << "known masses         " << l.known_masses << " declared\n";
  if (l.evidence > 0 || l.known_masses > 0) {
    out << "learnt scale         " << fixed(l.scale, 4) << " (std "
        << fixed(100.0 * l.relative_std, 2) << " %, from " << l.evidence << " drive"
        << (l.evidence == 1 ? "" : "s") << " on a known mass"
        << (l.changes > 0 ? ", " + std::to_string(l.changes) + " changes" : "") << ")\n";
  } else if (l.anchors > 0) {
    out << "learnt scale         " << fixed(l.scale, 4) << " (std "
        << fixed(100.0 * l.relative_std, 2) << " %, from " << l.anchors << " standstill reading"
        << (l.anchors == 1 ? "" : "s") << " of the load)\n";
  }
  if (l.gear_drives == 0) return;
  out << "learnt gear masses   from " << l.gear_drives << " drive"
      << (l.gear_drives == 1 ? "" : "s") << ":";
  for (std::size_t i = 0; i < l.gear_correction_kg.size(); ++i) {
    out << (i == 0 ? " " : ", ") << "gear " << i + 1 << " " << std::lround(l.gear_correction_kg[i])
        << " +- " << std::lround(l.gear_std_kg[i]) << " kg";
  }
  out << "\n";
}

// The configured rotating masses' and converter map's errors the drive's pairs tell, as
// fractions x (the true rotating masses, and the true multiplication TR - 1, are (1 + x) times
// the configured ones), and what they move the mass.
void pair_term_rows(const PairTermFit& f, std::ostringstream& out) {
  out << "pair-term fit        rotating masses " << signed_fixed(f.rotating_error, 3) << " +- "
      << fixed(f.rotating_error_std, 3);
  if (f.converter_multiplied) {
    out << ", converter map " << signed_fixed(-f.converter_error, 3) << " +- "
        << fixed(f.converter_error_std, 3);
  }
  out << ": mass " << signed_fixed(f.mass_shift_kg, 0) << " +- " << fixed(f.mass_std_kg, 0)
      << " kg (" << f.pairs << " pairs)\n";
}

// {"small_delta_force": 11160, "speed": 5400, ...}: why the block took no pair, by tick.
json::Json refusals_json(const VerdictTally& tally, Block block) {
  json::Json out = json::Json::object();
  for (const auto& [verdict, count] : tally.refusals(block)) {
    out[std::string(verdict_name(verdict))] = count;
  }
  return out;
}

// The final estimate, its prior, status and pairs, and each block's counters.
void estimate_fields(const ReplaySummary::Result& r, json::Json* j) {
  const Estimate& e = r.final_estimate;
  auto mass = [&](double v) { return r.has_estimate ? json::fixed(v, 3) : json::Json(); };
  (*j)["mass_kg"] = mass(e.mass_kg);
  (*j)["ci_low_kg"] = mass(e.ci_low_kg);
  (*j)["ci_high_kg"] = mass(e.ci_high_kg);
  (*j)["mass_std_kg"] = mass(e.mass_std_kg);
  (*j)["mu_n"] = mass(e.mu_n);
  (*j)["initial_mass_kg"] = mass(e.initial_mass_kg);
  (*j)["prior"] = std::string(reason_name(e.prior_reason));
  (*j)["reinitialisations"] = r.reinitialisations;
  (*j)["status"] = std::string(status_name(e.status));
  (*j)["reason"] = e.describe_reason();
  (*j)["pairs_used"] = e.pairs_used;
  (*j)["pairs_accepted"] = r.pairs_accepted;
  for (int b = 0; b < kBlockCount; ++b) {
    const BlockCounters& c = e.blocks[static_cast<std::size_t>(b)];
    const std::string key = kBlockKeys[b];
    (*j)[key + "_availability"] = json::fixed(c.availability(), 5);
    (*j)[key] = {{"ticks", c.ticks},
                 {"candidates", c.candidates},
                 {"accepted", c.accepted},
                 {"rejected_innovation", c.rejected_innovation},
                 {"refused", refusals_json(r.verdicts, static_cast<Block>(b))}};
  }
}

json::Json opt_json(const std::optional<double>& v, int digits) {
  return v ? json::fixed(*v, digits) : json::Json();
}

// Against the truth: null without one.
void truth_fields(const ReplaySummary::Result& r, json::Json* j) {
  const auto& within = r.time_within_since_first_tick_s;
  (*j)["true_mass_kg"] = opt_json(r.true_mass_kg, 3);
  (*j)["error_percent"] = opt_json(r.error_percent, 5);
  (*j)["time_within_5_s"] = opt_json(within[0], 3);
  (*j)["time_within_2_s"] = opt_json(within[1], 3);
  (*j)["time_within_1_s"] = opt_json(within[2], 3);
  (*j)["coverage"] = opt_json(r.coverage_of_dynamic_ticks, 5);
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
    case StatusReason::kKnownMass:
      return "a known mass the user declared";
    default:
      return "no prior";
  }
}

std::string replay_table(const ReplaySummary::Result& r, const std::string& estimator_name) {
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
    const std::string why = r.verdicts.describe_refusals(static_cast<Block>(b));
    if (!why.empty()) out << "  ticks without pair  " << why << " (verdicts)\n";
  }
  if (r.coarse_speed_interval_s) {
    out << "speed signal         changes every " << fixed(*r.coarse_speed_interval_s, 2)
        << " s as the speed changes: too coarse for its derivative, the rotating term read the "
           "accelerometer\n";
  }
  if (r.pair_terms) pair_term_rows(*r.pair_terms, out);
  if (r.learnt) learnt_rows(*r.learnt, out);
  if (r.true_mass_kg) truth_rows(r, out);
  return out.str();
}

std::string replay_json(const ReplaySummary::Result& r, const std::string& estimator_name) {
  json::Json j;
  j["estimator"] = estimator_name;
  j["duration_s"] = json::fixed(r.duration_s, 3);
  j["ticks"] = r.ticks;
  j["has_estimate"] = r.has_estimate;
  estimate_fields(r, &j);
  truth_fields(r, &j);
  if (r.coarse_speed_interval_s) {
    j["speed_signal"] = {{"coarse", true},
                         {"mean_change_interval_s", json::fixed(*r.coarse_speed_interval_s, 3)},
                         {"rotating_accel", "accelerometer"}};
  }
  if (r.pair_terms) {
    const PairTermFit& f = *r.pair_terms;
    j["pair_term_fit"] = {{"rotating_error", json::fixed(f.rotating_error, 6)},
                          {"rotating_error_std", json::fixed(f.rotating_error_std, 6)},
                          {"converter_multiplied", f.converter_multiplied},
                          {"converter_error", json::fixed(-f.converter_error, 6)},
                          {"converter_error_std", json::fixed(f.converter_error_std, 6)},
                          {"mass_shift_kg", json::fixed(f.mass_shift_kg, 3)},
                          {"mass_std_kg", json::fixed(f.mass_std_kg, 3)},
                          {"pairs", f.pairs}};
  }
  if (r.learnt) {
    j["learnt"] = {{"scale", json::fixed(r.learnt->scale, 6)},
                   {"scale_std", json::fixed(r.learnt->relative_std, 6)},
                   {"evidence", r.learnt->evidence},
                   {"changes", r.learnt->changes},
                   {"anchors", r.learnt->anchors},
                   {"known_masses", r.learnt->known_masses},
                   {"gear_drives", r.learnt->gear_drives}};
    json::Json gears = json::Json::array();
    for (std::size_t i = 0; i < r.learnt->gear_correction_kg.size(); ++i) {
      gears.push_back({{"gear", i + 1},
                       {"correction_kg", json::fixed(r.learnt->gear_correction_kg[i], 3)},
                       {"std_kg", json::fixed(r.learnt->gear_std_kg[i], 3)}});
    }
    j["learnt"]["gears"] = gears;
  }
  return json::dump(j);
}

}  // namespace vmass::scoring
