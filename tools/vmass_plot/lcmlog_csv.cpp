// vmass-lcmlog-csv: what vmassd published, recorded by lcm-logger (or vmassd --lcm-url
// file://RUN.lcmlog?mode=w), as CSV files vmass-plot plots. Read with LCM's own log reader
// (lcm::LogFile); the messages decoded with the generated vmass types.
//
//   vmass-lcmlog-csv LOG [--estimates CSV] [--status CSV] [--pairs CSV] [--estimate-channel C]
//                    [--status-channel C] [--pairs-channel C]
//
// The estimates CSV has vmass-replay's columns and number formats (docs/formats.md), so a
// recording of vmassd over a log compares byte for byte with vmass-replay --out over the same
// log; a row before the first estimate (mass_known false) leaves its mass cells empty. The
// status CSV has one row per status message: time_s, uptime_s, state, version, mass_kg, ticks,
// tick_overruns, jitter_p99_us, frames_received, frames_decoded, frames_malformed,
// inputs_valid (of num_inputs), num_inputs, then what is learnt about the car (learnt_*), the
// tyre watch (tyre_watch_*) and the drive's pair-term fit (pair_fit_*), as status_t carries
// them (kStatusHeader). The pairs CSV (vmassd with lcm.publish_pairs) has one row per candidate
// pair: time_s, block, verdict, accepted, y_n, delta_accel_mps2, weight, noise_std_n,
// rotating_n, rotating_mass_kg, gear, test_ratio (a per-gear study of the rotating masses reads
// it: tools/vmass_suite/pairs_by_gear.py). Exit codes: 0 ok, 1 a CSV cannot be written, 2 usage
// or a file that is not an LCM log; a message that does not decode is counted and skipped.
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>
#include <vmass/mass_estimate_t.hpp>
#include <vmass/pair_t.hpp>
#include <vmass/status_t.hpp>

#include "exit_code.hpp"

namespace {

using vmass::tools::kExitFailure;
using vmass::tools::kExitOk;
using vmass::tools::kExitUsage;

struct Options {
  std::string log, estimates_csv, status_csv, pairs_csv;
  std::string estimate_channel = "VMASS_ESTIMATE", status_channel = "VMASS_STATUS",
              pairs_channel = "VMASS_PAIRS";
};

struct Counts {
  long estimates = 0, statuses = 0, pairs = 0, undecodable = 0, other = 0;
};

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

File open_csv(const std::string& path, const char* header) {
  if (path.empty()) return {nullptr, &std::fclose};
  File f(std::fopen(path.c_str(), "w"), &std::fclose);
  if (f) std::fprintf(f.get(), "%s\n", header);
  return f;
}

/// The row vmass-replay writes for the same estimate (vmass::EstimateCsvWriter::row).
void write_estimate(std::FILE* f, const vmass::mass_estimate_t& e) {
  char mass[160] = ",,,";
  char std_kg[32] = "";
  char initial[32] = "";
  if (e.mass_known) {
    std::snprintf(mass, sizeof mass, "%.3f,%.3f,%.3f,%.3f", e.mass_kg, e.mass_ci_low_kg,
                  e.mass_ci_high_kg, e.mu_n);
    std::snprintf(std_kg, sizeof std_kg, "%.3f", e.mass_std_kg);
    std::snprintf(initial, sizeof initial, "%.3f", e.initial_mass_kg);
  }
  std::fprintf(f, "%.2f,%s,%s,%s,%s,%lld,%lld,%.5f,%.5f,%s\n", static_cast<double>(e.utime) * 1e-6,
               mass, e.status_name.c_str(), std_kg, e.reason_name.c_str(),
               static_cast<long long>(e.longitudinal_accepted),
               static_cast<long long>(e.lateral_accepted), e.longitudinal_availability,
               e.lateral_availability, initial);
}

/// The status CSV's columns: the daemon's health, then what is learnt about the car, the tyre
/// watch and the drive's pair-term fit (schema 8).
constexpr const char* kStatusHeader =
    "time_s,uptime_s,state,version,mass_kg,ticks,tick_overruns,jitter_p99_us,frames_received,"
    "frames_decoded,frames_malformed,inputs_valid,num_inputs,"
    "learnt_scale,learnt_scale_std,learnt_evidence,learnt_changes,learnt_anchors,"
    "learnt_tyre_changes,learnt_gear_drives,"
    "tyre_watch_launches,tyre_watch_stops,tyre_watch_changes,tyre_watch_step,"
    "tyre_watch_step_sigma,tyre_watch_suspected,"
    "pair_fit_applies,pair_fit_pairs,pair_fit_rotating_error,pair_fit_rotating_error_std,"
    "pair_fit_converter_multiplied,pair_fit_converter_error,pair_fit_converter_error_std,"
    "pair_fit_shift_kg,pair_fit_shift_std_kg";

long long as_ll(std::int64_t v) { return static_cast<long long>(v); }

void write_status(std::FILE* f, const vmass::status_t& s) {
  int valid = 0;
  for (bool v : s.input_valid) valid += v ? 1 : 0;
  std::fprintf(f, "%.2f,%.3f,%s,%s,%.3f,%lld,%lld,%.1f,%lld,%lld,%lld,%d,%d,",
               static_cast<double>(s.utime) * 1e-6, s.uptime_s, s.state_name.c_str(),
               s.version.c_str(), s.mass_kg, as_ll(s.ticks), as_ll(s.tick_overruns),
               s.jitter_p99_us, as_ll(s.frames_received), as_ll(s.frames_decoded),
               as_ll(s.frames_malformed), valid, s.num_inputs);
  std::fprintf(f, "%.6f,%.6f,%lld,%lld,%lld,%lld,%lld,", s.learnt_scale, s.learnt_scale_std,
               as_ll(s.learnt_evidence), as_ll(s.learnt_changes), as_ll(s.learnt_anchors),
               as_ll(s.learnt_tyre_changes), as_ll(s.learnt_gear_drives));
  std::fprintf(f, "%lld,%lld,%lld,%.6f,%.3f,%d,", as_ll(s.tyre_watch_launches),
               as_ll(s.tyre_watch_stops), as_ll(s.tyre_watch_changes), s.tyre_watch_step,
               s.tyre_watch_step_sigma, s.tyre_watch_suspected ? 1 : 0);
  std::fprintf(f, "%d,%lld,%.6f,%.6f,%d,%.6f,%.6f,%.3f,%.3f\n", s.pair_fit_applies ? 1 : 0,
               as_ll(s.pair_fit_pairs), s.pair_fit_rotating_error, s.pair_fit_rotating_error_std,
               s.pair_fit_converter_multiplied ? 1 : 0, s.pair_fit_converter_error,
               s.pair_fit_converter_error_std, s.pair_fit_shift_kg, s.pair_fit_shift_std_kg);
}

/// A candidate pair (the ticks where a block offered none are not written).
void write_pair(std::FILE* f, const vmass::pair_t& p) {
  std::fprintf(f, "%.2f,%s,%s,%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d,%.6g\n",
               static_cast<double>(p.utime) * 1e-6, p.block_name.c_str(), p.verdict_name.c_str(),
               p.accepted ? 1 : 0, p.y_n, p.delta_accel_mps2, p.weight, p.noise_std_n, p.rotating_n,
               p.rotating_mass_kg, static_cast<int>(p.gear), p.test_ratio);
}

/// Decodes one event into `msg`; false (counted) when it does not decode.
template <typename Message>
bool decode(const lcm::LogEvent& event, Message* msg, Counts* counts) {
  if (msg->decode(event.data, 0, event.datalen) == event.datalen) return true;
  ++counts->undecodable;
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vmass-lcmlog-csv: vmassd's estimates and status from an LCM log, as CSV"};
  Options o;
  app.add_option("log", o.log, "LCM log (lcm-logger)")->required();
  app.add_option("--estimates", o.estimates_csv, "write the estimates here (vmass-replay's CSV)");
  app.add_option("--status", o.status_csv, "write the status messages here");
  app.add_option("--estimate-channel", o.estimate_channel, "default VMASS_ESTIMATE");
  app.add_option("--status-channel", o.status_channel, "default VMASS_STATUS");
  app.add_option("--pairs", o.pairs_csv,
                 "write the candidate pairs here (vmassd with lcm.publish_pairs: true)");
  app.add_option("--pairs-channel", o.pairs_channel, "default VMASS_PAIRS");
  if (const auto code = vmass::tools::parse_command_line(app, argc, argv)) return *code;

  lcm::LogFile log(o.log, "r");
  const lcm::LogEvent* event = log.good() ? log.readNextEvent() : nullptr;
  if (event == nullptr) {
    std::cerr << "vmass-lcmlog-csv: " << o.log << ": not an LCM log, or empty\n";
    return kExitUsage;
  }
  File est = open_csv(o.estimates_csv,
                      "time_s,mass_kg,mass_ci_low_kg,mass_ci_high_kg,mu_n,status,mass_std_kg,"
                      "reason,longitudinal_pairs,lateral_pairs,longitudinal_availability,"
                      "lateral_availability,initial_mass_kg");
  File st = open_csv(o.status_csv, kStatusHeader);
  File pairs = open_csv(o.pairs_csv,
                        "time_s,block,verdict,accepted,y_n,delta_accel_mps2,weight,noise_std_n,"
                        "rotating_n,rotating_mass_kg,gear,test_ratio");
  if ((!o.estimates_csv.empty() && !est) || (!o.status_csv.empty() && !st) ||
      (!o.pairs_csv.empty() && !pairs)) {
    std::cerr << "vmass-lcmlog-csv: cannot write the CSV\n";
    return kExitFailure;
  }
  Counts counts;
  vmass::mass_estimate_t e;
  vmass::status_t s;
  vmass::pair_t pair;
  for (; event != nullptr; event = log.readNextEvent()) {
    if (event->channel == o.estimate_channel) {
      if (!decode(*event, &e, &counts)) continue;
      ++counts.estimates;
      if (est) write_estimate(est.get(), e);
    } else if (event->channel == o.status_channel) {
      if (!decode(*event, &s, &counts)) continue;
      ++counts.statuses;
      if (st) write_status(st.get(), s);
    } else if (event->channel == o.pairs_channel) {
      if (!decode(*event, &pair, &counts)) continue;
      ++counts.pairs;
      if (pairs && pair.has_candidate) write_pair(pairs.get(), pair);
    } else {
      ++counts.other;
    }
  }
  const bool written = (!est || std::fflush(est.get()) == 0) &&
                       (!st || std::fflush(st.get()) == 0) &&
                       (!pairs || std::fflush(pairs.get()) == 0);
  std::cerr << "vmass-lcmlog-csv: " << o.log << ": " << counts.estimates << " estimates, "
            << counts.statuses << " status messages, " << counts.pairs << " pair records, "
            << counts.other << " on other channels, " << counts.undecodable
            << " that do not decode\n";
  return written ? kExitOk : kExitFailure;
}
