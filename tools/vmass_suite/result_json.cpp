#include "result_json.hpp"

#include <cmath>

namespace vmass::suite {

namespace {

nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

}  // namespace

void add_result_fields(const EstimatorResult& r, nlohmann::json* out) {
  nlohmann::json& j = *out;
  const AccuracyResult& a = r.accuracy;
  j["knowledge"] = std::string(sim::knowledge_name(r.knowledge));
  j["estimator"] = r.estimator;
  j["supported"] = r.supported;
  if (!r.supported) {
    j["unsupported_reason"] = r.unsupported_reason;
    return;
  }
  j["has_estimate"] = a.has_estimate;
  j["final_mass_kg"] = number(a.final_mass_kg);
  j["true_final_mass_kg"] = number(a.true_final_mass_kg);
  j["final_error_pct"] = number(a.final_error_pct);
  j["error_20s_pct"] = number(a.error_at_pct[0]);
  j["error_60s_pct"] = number(a.error_at_pct[1]);
  j["time_within_5_s"] = number(a.time_within_since_drive_start_s[0]);
  j["time_within_2_s"] = number(a.time_within_since_drive_start_s[1]);
  j["time_within_1_s"] = number(a.time_within_since_drive_start_s[2]);
  j["rms_last_half_pct"] = number(a.rms_last_half_pct);
  j["covered_20s"] = a.covered_at_checkpoint[0];
  j["covered_60s"] = a.covered_at_checkpoint[1];
  j["covered_end"] = a.covered_at_end;
  j["halfwidth_end_pct"] = number(a.halfwidth_end_pct);
  j["converged_outside_fraction"] = number(a.converged_outside_fraction);
  j["availability_longitudinal"] = number(r.availability_longitudinal);
  j["availability_lateral"] = number(r.availability_lateral);
  j["accepted_longitudinal"] = r.accepted_longitudinal;
  j["accepted_lateral"] = r.accepted_lateral;
  j["pairs_used"] = r.pairs_used;
  j["status_end"] = r.status_end;
  j["reason_end"] = r.reason_end;
  j["initial_mass_kg"] = number(r.initial_mass_kg);
  j["identified_lag_s"] = number(r.identified_lag_s);
  j["accel_noise_mps2"] = number(r.accel_noise_mps2);
  j["rotating_error"] = number(r.rotating_error);
  j["rotating_error_std"] = number(r.rotating_error_std);
  j["pair_term_shift_kg"] = number(r.pair_term_shift_kg);
  if (!r.rotating_accel.empty()) j["rotating_accel"] = r.rotating_accel;
  j["speed_refresh_s"] = number(r.speed_refresh_s);
  // Why each block took no pair: its verdicts other than accepted, ticks (vmass only).
  for (const Block block : {Block::kLongitudinal, Block::kLateral}) {
    nlohmann::json refused = nlohmann::json::object();
    for (const auto& [verdict, ticks] : r.verdicts.refusals(block)) {
      refused[std::string(verdict_name(verdict))] = ticks;
    }
    if (!refused.empty()) j["refused_" + std::string(block_name(block))] = refused;
  }
}

}  // namespace vmass::suite
