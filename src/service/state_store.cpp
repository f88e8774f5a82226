#include "vmass/service/state_store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>

#include "vmass/io/regular_file.hpp"

namespace vmass::service {
namespace {

constexpr const char* kMagic = "vmass-state";
constexpr int kVersion = 8;
/// Still read: all but the tyre watch (nothing watched yet).
constexpr int kVersionWithoutTyreWatch = 7;
/// Still read: all but the current load's pair-term fit (it does not apply).
constexpr int kVersionWithoutPairTerms = 6;
/// Still read: all but the tyre changes (none; every known mass counts as since the tyres).
constexpr int kVersionWithoutTyres = 5;
constexpr int kVersionWithoutAnchors = 4;  ///< still read: all but the static anchors (none)
/// Still read: the learnt scale; its gear masses' reference was in kg, not relative to the mass,
/// and is not taken (the gears are learnt again).
constexpr int kVersionKgReference = 3;
constexpr int kVersionWithoutGears = 2;   ///< still read: the learnt scale, no gear masses
constexpr int kVersionWithoutLearnt = 1;  ///< still read: nothing learnt in it

std::uint64_t fnv1a(const char* data, std::size_t size, std::uint64_t h = 0xcbf29ce484222325ull) {
  for (std::size_t i = 0; i < size; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 0x100000001b3ull;
  }
  return h;
}

void put(std::string* out, const char* key, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  *out += key;
  *out += ' ';
  *out += buf;
  *out += '\n';
}

/// `key v1 v2 ...` on one line.
void put_list(std::string* out, const char* key, const double* v, int count) {
  *out += key;
  char buf[64];
  for (int i = 0; i < count; ++i) {
    std::snprintf(buf, sizeof buf, " %.17g", v[i]);
    *out += buf;
  }
  *out += '\n';
}

void put_int(std::string* out, const char* key, long long v) {
  *out += key;
  *out += ' ';
  *out += std::to_string(v);
  *out += '\n';
}

std::string errno_text(const std::string& what, const std::string& path) {
  return path + ": " + what + ": " + std::strerror(errno);
}

/// The saved-state file's fields after `type` and `prior_reason`: the one list that
/// format_state writes and parse_state reads (the file's order).
struct StateField {
  enum class Kind : std::uint8_t { kReal, kInteger, kFlag };
  const char* key;
  Kind kind;
  double* (*real)(PipelineSnapshot&);
  long* (*integer)(PipelineSnapshot&);
  bool* (*flag)(PipelineSnapshot&);
};

constexpr StateField real(const char* key, double* (*at)(PipelineSnapshot&)) {
  return {key, StateField::Kind::kReal, at, nullptr, nullptr};
}
constexpr StateField integer(const char* key, long* (*at)(PipelineSnapshot&)) {
  return {key, StateField::Kind::kInteger, nullptr, at, nullptr};
}
constexpr StateField flag(const char* key, bool* (*at)(PipelineSnapshot&)) {
  return {key, StateField::Kind::kFlag, nullptr, nullptr, at};
}

using S = PipelineSnapshot;
constexpr StateField kStateFields[] = {
    flag("has_prior", [](S& s) { return &s.has_prior; }),
    real("prior_mass_kg", [](S& s) { return &s.prior.mass_kg; }),
    real("prior_mass_std_kg", [](S& s) { return &s.prior.mass_std_kg; }),
    real("prior_mu_n", [](S& s) { return &s.prior.mu_n; }),
    real("prior_mu_std_n", [](S& s) { return &s.prior.mu_std_n; }),
    integer("pairs_used", [](S& s) { return &s.pairs_used; }),
    real("rls_theta_0", [](S& s) { return &s.rls_theta[0]; }),
    real("rls_theta_1", [](S& s) { return &s.rls_theta[1]; }),
    real("rls_covariance_0", [](S& s) { return &s.rls_covariance[0]; }),
    real("rls_covariance_1", [](S& s) { return &s.rls_covariance[1]; }),
    real("rls_covariance_2", [](S& s) { return &s.rls_covariance[2]; }),
    real("rls_covariance_3", [](S& s) { return &s.rls_covariance[3]; }),
    real("nig_mean_0", [](S& s) { return &s.nig_mean[0]; }),
    real("nig_mean_1", [](S& s) { return &s.nig_mean[1]; }),
    real("nig_scaled_covariance_0", [](S& s) { return &s.nig_scaled_covariance[0]; }),
    real("nig_scaled_covariance_1", [](S& s) { return &s.nig_scaled_covariance[1]; }),
    real("nig_scaled_covariance_2", [](S& s) { return &s.nig_scaled_covariance[2]; }),
    real("nig_scaled_covariance_3", [](S& s) { return &s.nig_scaled_covariance[3]; }),
    real("nig_shape", [](S& s) { return &s.nig_shape; }),
    real("nig_scale", [](S& s) { return &s.nig_scale; }),
    flag("has_reference", [](S& s) { return &s.has_reference; }),
    real("reference_deflection_m", [](S& s) { return &s.reference_deflection_m; }),
    real("reference_deflection_std_m", [](S& s) { return &s.reference_deflection_std_m; }),
    integer("longitudinal_ticks", [](S& s) { return &s.blocks[0].ticks; }),
    integer("longitudinal_candidates", [](S& s) { return &s.blocks[0].candidates; }),
    integer("longitudinal_accepted", [](S& s) { return &s.blocks[0].accepted; }),
    integer("longitudinal_rejected_innovation",
            [](S& s) { return &s.blocks[0].rejected_innovation; }),
    integer("lateral_ticks", [](S& s) { return &s.blocks[1].ticks; }),
    integer("lateral_candidates", [](S& s) { return &s.blocks[1].candidates; }),
    integer("lateral_accepted", [](S& s) { return &s.blocks[1].accepted; }),
    integer("lateral_rejected_innovation", [](S& s) { return &s.blocks[1].rejected_innovation; }),
};
/// Format version 2: what is learnt about the car (LearntScale), the known mass of the load.
constexpr StateField kLearntFields[] = {
    real("learnt_log_scale", [](S& s) { return &s.learnt.log_scale; }),
    real("learnt_log_scale_var", [](S& s) { return &s.learnt.log_scale_var; }),
    integer("learnt_evidence", [](S& s) { return &s.learnt.evidence; }),
    integer("learnt_changes", [](S& s) { return &s.learnt.changes; }),
    integer("learnt_pending_outlier_sign", [](S& s) { return &s.learnt.pending_outlier_sign; }),
    real("learnt_pending_log_scale", [](S& s) { return &s.learnt.pending_log_scale; }),
    real("learnt_pending_var", [](S& s) { return &s.learnt.pending_var; }),
    real("pair_scale", [](S& s) { return &s.pair_scale; }),
    flag("known_mass_active", [](S& s) { return &s.known_mass.active; }),
    real("known_mass_kg", [](S& s) { return &s.known_mass.mass_kg; }),
    real("known_mass_std_kg", [](S& s) { return &s.known_mass.std_kg; }),
    real("known_mass_scale_used", [](S& s) { return &s.known_mass.scale_used; }),
};
/// Format version 5: the learnt scale's static anchors (LearntScaleState), and the current
/// load's anchor's evidence so far (taken at the next power cycle).
constexpr StateField kAnchorFields[] = {
    real("learnt_anchor_weight", [](S& s) { return &s.learnt.anchor_weight; }),
    real("learnt_anchor_weighted_log_scale",
         [](S& s) { return &s.learnt.anchor_weighted_log_scale; }),
    real("learnt_anchor_weighted_common_std",
         [](S& s) { return &s.learnt.anchor_weighted_common_std; }),
    integer("learnt_anchors", [](S& s) { return &s.learnt.anchors; }),
    flag("static_anchor_pending", [](S& s) { return &s.static_anchor_pending; }),
    real("static_anchor_log_scale", [](S& s) { return &s.static_anchor.log_scale; }),
    real("static_anchor_variance", [](S& s) { return &s.static_anchor.variance; }),
    real("static_anchor_common_std", [](S& s) { return &s.static_anchor.common_std; }),
};
/// Format version 6: the tyre changes declared, and the known masses since the last one.
constexpr StateField kTyreFields[] = {
    integer("learnt_tyre_changes", [](S& s) { return &s.learnt.tyre_changes; }),
    integer("learnt_evidence_since_tyres", [](S& s) { return &s.learnt.evidence_since_tyres; }),
};
static_assert(kBlockCount == 2, "kStateFields lists the counters of two blocks");
/// Optional (files from before the grade check): "nan" or absent = unknown grade.
constexpr const char* kGradeKey = "reference_grade_accel_mps2";

}  // namespace

std::uint64_t state_fingerprint(const PipelineParams& p) {
  const VehicleParams& v = p.vehicle;
  const SuspensionParams& s = p.suspension;
  std::string text = std::string(regressor_type_name(p.estimator.type));
  put(&text, "x", s.carries_load() ? 1.0 : 0.0);
  for (double x : {v.empty_mass_kg, v.wheelbase_m, v.cg_to_front_axle_m, v.gravity_mps2,
                   s.stiffness_n_per_m, s.empty_deflection_m, s.progressive_knee_m,
                   s.progressive_rate_n_per_m2, s.linear_range_kg, s.calibrated_range_kg}) {
    put(&text, "x", x);
  }
  return fnv1a(text.data(), text.size());
}

namespace {

void write_field(std::string* out, const StateField& field, PipelineSnapshot& s) {
  switch (field.kind) {
    case StateField::Kind::kReal:
      put(out, field.key, *field.real(s));
      break;
    case StateField::Kind::kInteger:
      put_int(out, field.key, *field.integer(s));
      break;
    case StateField::Kind::kFlag:
      put_int(out, field.key, *field.flag(s) ? 1 : 0);
      break;
  }
}

/// Format version 4: the learnt gear masses (LearntGearMasses), the covariance row-major.
void write_gear_masses(std::string* out, const GearMassesState& g) {
  put_int(out, "learnt_gears", g.gears);
  put_int(out, "learnt_gear_drives", g.drives);
  put(out, "learnt_gear_reference_precision", g.reference_precision);
  put(out, "learnt_gear_reference_applied", g.reference_applied);
  if (g.gears == 0) return;  // a line needs a value
  put_list(out, "learnt_gear_correction_kg", g.correction_kg.data(), g.gears);
  put_list(out, "learnt_gear_reference_share_per_kg", g.reference_share_per_kg.data(), g.gears);
  for (int i = 0; i < g.gears; ++i) {
    const std::string key = "learnt_gear_covariance_kg2_" + std::to_string(i + 1);
    put_list(out, key.c_str(), g.covariance_kg2.data() + i * kMaxLearntGears, g.gears);
  }
}

/// Format version 8: the launches' and stops' log s (TyreWatchState): each SpanSums as
/// "count sum sum_sq" of the launches, then of the stops.
void put_launches(std::string* out, const char* key, const SpanSums& l) {
  const LaunchSums& a = l.kind[0];
  const LaunchSums& b = l.kind[1];
  const double v[6] = {a.count, a.sum, a.sum_sq, b.count, b.sum, b.sum_sq};
  put_list(out, key, v, 6);
}

void write_tyre_watch(std::string* out, const TyreWatchState& t) {
  put_launches(out, "tyre_watch_settled", t.settled);
  put_int(out, "tyre_watch_window_drives", t.window_drives);
  for (long i = 0; i < t.window_drives; ++i) {
    const std::string key = "tyre_watch_window_" + std::to_string(i + 1);
    put_launches(out, key.c_str(), t.window[static_cast<std::size_t>(i)]);
  }
  put_launches(out, "tyre_watch_drive", t.drive);
  put(out, "tyre_watch_spread_sum_sq", t.spread_sum_sq);
  put(out, "tyre_watch_spread_dof", t.spread_dof);
  put_int(out, "tyre_watch_changes", t.changes);
}

/// Format version 7: the current load's pair-term fit (PairTermSums), the normal matrix row-major.
void write_pair_terms(std::string* out, const PipelineSnapshot& s) {
  put_int(out, "pair_term_fit_applies", s.pair_term_fit_applies ? 1 : 0);
  put_int(out, "pair_term_pairs", s.pair_term_sums.pairs);
  put_list(out, "pair_term_normal", s.pair_term_sums.normal.data(), 16);
  put_list(out, "pair_term_moment", s.pair_term_sums.moment.data(), 4);
}

}  // namespace

std::uint64_t learnt_fingerprint(const PipelineParams& p) {
  const VehicleParams& v = p.vehicle;
  std::string text = "learnt";
  for (double x : {v.wheel_radius_m, v.final_drive_ratio, v.driveline_efficiency,
                   v.pitch_gradient_deg_per_g, v.rotating_mass_kg, v.brake_gain_n_per_pa,
                   v.drag_area_m2, v.rolling_resistance_coeff, v.gravity_mps2}) {
    put(&text, "x", x);
  }
  for (double x : v.gear_ratios) put(&text, "gear", x);
  for (double x : v.rotating_mass_by_gear_kg) put(&text, "rotating", x);
  put(&text, "electric", v.electric_drive ? 1.0 : 0.0);
  // A derived ratio's force carries the speed signal's scale, not the radius's: another car's
  // scale. Only then, so that every other config keeps its fingerprint.
  if (v.derive_overall_ratio) put(&text, "derived_ratio", v.engine_inertia_kgm2);
  // Pairs read through a converter's map carry its curve; only then, for the same reason.
  if (v.knows_converter_map()) {
    put(&text, "converter", v.torque_converter_stall_torque_ratio);
    put(&text, "coupling", v.torque_converter_coupling_speed_ratio);
  }
  return fnv1a(text.data(), text.size());
}

std::string format_state(const SavedState& state) {
  PipelineSnapshot s = state.snapshot;  // the table's accessors take a mutable snapshot
  std::string out;
  out += std::string(kMagic) + " " + std::to_string(kVersion) + "\n";
  char hex[32];
  std::snprintf(hex, sizeof hex, "%016" PRIx64, state.fingerprint);
  out += std::string("fingerprint ") + hex + "\n";
  put_int(&out, "saved_time_us", state.saved_time_us);
  out += std::string("type ") + std::string(regressor_type_name(s.type)) + "\n";
  put_int(&out, "prior_reason", static_cast<int>(s.prior_reason));
  for (const StateField& field : kStateFields) write_field(&out, field, s);
  put(&out, kGradeKey, s.reference_grade_accel_mps2);  // may be nan
  std::snprintf(hex, sizeof hex, "%016" PRIx64, state.learnt_fingerprint);
  out += std::string("learnt_fingerprint ") + hex + "\n";
  for (const StateField& field : kLearntFields) write_field(&out, field, s);
  for (const StateField& field : kAnchorFields) write_field(&out, field, s);
  for (const StateField& field : kTyreFields) write_field(&out, field, s);
  write_gear_masses(&out, s.gear_masses);
  write_pair_terms(&out, s);
  write_tyre_watch(&out, s.tyre_watch);
  std::snprintf(hex, sizeof hex, "%016" PRIx64, fnv1a(out.data(), out.size()));
  out += std::string("checksum ") + hex + "\n";
  return out;
}

namespace {

using Values = std::map<std::string, std::string>;

/// The checksum line matches the text before it. "" when it does, else why not.
std::string check_checksum(const std::string& text, std::size_t* checksum_at) {
  *checksum_at = text.rfind("checksum ");
  if (*checksum_at == std::string::npos || (*checksum_at > 0 && text[*checksum_at - 1] != '\n')) {
    return "no checksum line (truncated file?)";
  }
  std::uint64_t expected = 0;
  const char* begin = text.data() + *checksum_at + 9;
  const char* end = text.data() + text.size();
  while (end > begin && (end[-1] == '\n' || end[-1] == '\r')) --end;
  const auto r = std::from_chars(begin, end, expected, 16);
  if (r.ec != std::errc() || r.ptr != end) return "malformed checksum line";
  if (fnv1a(text.data(), *checksum_at) != expected) return "checksum mismatch (corrupt file)";
  return "";
}

/// "key value" lines into a map. "" on success, else "line N: ...".
std::string split_lines(const std::string& text, Values* values) {
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::size_t space = line.find(' ');
    if (space == std::string::npos) {
      return "line " + std::to_string(line_no) + ": expected 'key value'";
    }
    (*values)[line.substr(0, space)] = line.substr(space + 1);
  }
  return "";
}

/// Typed reads of the values; each returns "" or why the key is missing or malformed.
struct ValueReader {
  const Values& values;

  std::string text(const std::string& key, std::string* out) const {
    const auto it = values.find(key);
    if (it == values.end()) return "missing key " + key;
    *out = it->second;
    return "";
  }
  std::string real(const std::string& key, double* out) const {
    std::string v;
    if (std::string e = text(key, &v); !e.empty()) return e;
    const auto r = std::from_chars(v.data(), v.data() + v.size(), *out);
    // from_chars does not read "inf"/"nan" spellings of every libc; they are invalid here.
    if (r.ec != std::errc() || r.ptr != v.data() + v.size()) {
      return key + ": not a number: '" + v + "'";
    }
    return "";
  }
  /// `count` numbers on the key's line.
  std::string reals(const std::string& key, int count, double* out) const {
    std::string v;
    if (std::string e = text(key, &v); !e.empty()) return e;
    const char* at = v.data();
    const char* end = v.data() + v.size();
    for (int i = 0; i < count; ++i) {
      while (at < end && *at == ' ') ++at;
      const auto r = std::from_chars(at, end, out[i]);
      if (r.ec != std::errc() || (r.ptr != end && *r.ptr != ' ')) {
        return key + ": expected " + std::to_string(count) + " numbers: '" + v + "'";
      }
      at = r.ptr;
    }
    while (at < end && *at == ' ') ++at;
    if (at != end) return key + ": more than " + std::to_string(count) + " numbers";
    return "";
  }
  std::string integer(const std::string& key, long long* out) const {
    std::string v;
    if (std::string e = text(key, &v); !e.empty()) return e;
    const auto r = std::from_chars(v.data(), v.data() + v.size(), *out);
    if (r.ec != std::errc() || r.ptr != v.data() + v.size()) {
      return key + ": not an integer: '" + v + "'";
    }
    return "";
  }
};

/// A reason a belief can have started from (Pipeline::restart, restore): a car without a load
/// sensor saves no_load_sensor, which comes after restored in the enumeration.
bool starts_a_belief(long long n) {
  switch (n) {
    case static_cast<long long>(StatusReason::kWaitingForStandstill):
    case static_cast<long long>(StatusReason::kStaticInitialised):
    case static_cast<long long>(StatusReason::kLoadChanged):
    case static_cast<long long>(StatusReason::kNoStaticPrior):
    case static_cast<long long>(StatusReason::kRestored):
    case static_cast<long long>(StatusReason::kNoLoadSensor):
    case static_cast<long long>(StatusReason::kKnownMass):
      return true;
    default:
      return false;
  }
}

/// fingerprint, saved_time_us, type and prior_reason: the fields outside the table.
std::string read_header_fields(const ValueReader& in, SavedState* out) {
  std::string fingerprint, type;
  long long n = 0;
  if (std::string e = in.text("fingerprint", &fingerprint); !e.empty()) return e;
  const auto r = std::from_chars(fingerprint.data(), fingerprint.data() + fingerprint.size(),
                                 out->fingerprint, 16);
  if (r.ec != std::errc()) return "fingerprint: not hexadecimal";
  if (std::string e = in.integer("saved_time_us", &n); !e.empty()) return e;
  out->saved_time_us = n;
  if (std::string e = in.text("type", &type); !e.empty()) return e;
  if (type != "rls" && type != "bayes") return "type: expected rls or bayes, got '" + type + "'";
  out->snapshot.type = type == "rls" ? RegressorType::kRls : RegressorType::kBayes;
  if (std::string e = in.integer("prior_reason", &n); !e.empty()) return e;
  if (!starts_a_belief(n)) return "prior_reason: out of range";
  out->snapshot.prior_reason = static_cast<StatusReason>(n);
  return "";
}

std::string read_pair_terms(const ValueReader& in, PipelineSnapshot* s) {
  long long n = 0;
  if (std::string e = in.integer("pair_term_fit_applies", &n); !e.empty()) return e;
  if (n != 0 && n != 1) return "pair_term_fit_applies: not 0 or 1";
  s->pair_term_fit_applies = n == 1;
  if (std::string e = in.integer("pair_term_pairs", &n); !e.empty()) return e;
  s->pair_term_sums.pairs = static_cast<long>(n);
  if (std::string e = in.reals("pair_term_normal", 16, s->pair_term_sums.normal.data());
      !e.empty()) {
    return e;
  }
  return in.reals("pair_term_moment", 4, s->pair_term_sums.moment.data());
}

std::string read_launches(const ValueReader& in, const std::string& key, SpanSums* l) {
  double v[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  if (std::string e = in.reals(key, 6, v); !e.empty()) return e;
  l->kind[0] = LaunchSums{v[0], v[1], v[2]};
  l->kind[1] = LaunchSums{v[3], v[4], v[5]};
  return "";
}

std::string read_tyre_watch(const ValueReader& in, TyreWatchState* t) {
  if (std::string e = read_launches(in, "tyre_watch_settled", &t->settled); !e.empty()) return e;
  long long n = 0;
  if (std::string e = in.integer("tyre_watch_window_drives", &n); !e.empty()) return e;
  if (n < 0 || n > kTyreWatchWindowDrives) return "tyre_watch_window_drives: out of range";
  t->window_drives = static_cast<long>(n);
  for (long i = 0; i < t->window_drives; ++i) {
    const std::string key = "tyre_watch_window_" + std::to_string(i + 1);
    if (std::string e = read_launches(in, key, &t->window[static_cast<std::size_t>(i)]);
        !e.empty()) {
      return e;
    }
  }
  if (std::string e = read_launches(in, "tyre_watch_drive", &t->drive); !e.empty()) return e;
  if (std::string e = in.real("tyre_watch_spread_sum_sq", &t->spread_sum_sq); !e.empty()) return e;
  if (std::string e = in.real("tyre_watch_spread_dof", &t->spread_dof); !e.empty()) return e;
  if (std::string e = in.integer("tyre_watch_changes", &n); !e.empty()) return e;
  t->changes = static_cast<long>(n);
  return "";
}

std::string read_gear_masses(const ValueReader& in, GearMassesState* g) {
  long long n = 0;
  if (std::string e = in.integer("learnt_gears", &n); !e.empty()) return e;
  if (n < 0 || n > kMaxLearntGears) return "learnt_gears: out of range";
  g->gears = static_cast<int>(n);
  if (std::string e = in.integer("learnt_gear_drives", &n); !e.empty()) return e;
  g->drives = static_cast<long>(n);
  if (std::string e = in.real("learnt_gear_reference_precision", &g->reference_precision);
      !e.empty()) {
    return e;
  }
  if (std::string e = in.real("learnt_gear_reference_applied", &g->reference_applied); !e.empty()) {
    return e;
  }
  if (g->gears == 0) return "";
  if (std::string e = in.reals("learnt_gear_correction_kg", g->gears, g->correction_kg.data());
      !e.empty()) {
    return e;
  }
  if (std::string e = in.reals("learnt_gear_reference_share_per_kg", g->gears,
                               g->reference_share_per_kg.data());
      !e.empty()) {
    return e;
  }
  for (int i = 0; i < g->gears; ++i) {
    const std::string key = "learnt_gear_covariance_kg2_" + std::to_string(i + 1);
    double* row = g->covariance_kg2.data() + i * kMaxLearntGears;
    if (std::string e = in.reals(key, g->gears, row); !e.empty()) return e;
  }
  return "";
}

std::string read_table_field(const ValueReader& in, const StateField& field, PipelineSnapshot* s) {
  long long n = 0;
  switch (field.kind) {
    case StateField::Kind::kReal:
      return in.real(field.key, field.real(*s));
    case StateField::Kind::kInteger:
      if (std::string e = in.integer(field.key, &n); !e.empty()) return e;
      *field.integer(*s) = static_cast<long>(n);
      return "";
    case StateField::Kind::kFlag:
      if (std::string e = in.integer(field.key, &n); !e.empty()) return e;
      *field.flag(*s) = n != 0;
      return "";
  }
  return "";
}

}  // namespace

bool parse_state(const std::string& text, SavedState* state, std::string* error) {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  std::size_t checksum_at = 0;
  if (std::string e = check_checksum(text, &checksum_at); !e.empty()) return fail(e);
  Values values;
  if (std::string e = split_lines(text.substr(0, checksum_at), &values); !e.empty()) {
    return fail(e);
  }
  const std::string& version_text = values[kMagic];
  int version = 0;
  for (int known :
       {kVersion, kVersionWithoutTyreWatch, kVersionWithoutPairTerms, kVersionWithoutTyres,
        kVersionWithoutAnchors, kVersionKgReference, kVersionWithoutGears, kVersionWithoutLearnt}) {
    if (version_text == std::to_string(known)) version = known;
  }
  if (version == 0) {
    return fail("not a vmass state file of format version " + std::to_string(kVersion) + " to " +
                std::to_string(kVersionWithoutLearnt));
  }
  const ValueReader in{values};
  SavedState out;
  if (std::string e = read_header_fields(in, &out); !e.empty()) return fail(e);
  for (const StateField& field : kStateFields) {
    if (std::string e = read_table_field(in, field, &out.snapshot); !e.empty()) return fail(e);
  }
  out.snapshot.reference_grade_accel_mps2 = std::numeric_limits<double>::quiet_NaN();
  const auto grade = values.find(kGradeKey);
  if (grade != values.end() && grade->second != "nan" && grade->second != "-nan") {
    if (std::string e = in.real(kGradeKey, &out.snapshot.reference_grade_accel_mps2); !e.empty()) {
      return fail(e);
    }
  }
  out.snapshot.learnt_saved = version != kVersionWithoutLearnt;
  out.snapshot.gear_masses_saved = version >= kVersionWithoutAnchors;
  const bool anchors_saved = version >= kVersionWithoutTyres;
  const bool tyres_saved = version >= kVersionWithoutPairTerms;
  if (out.snapshot.learnt_saved) {
    std::string hex;
    if (std::string e = in.text("learnt_fingerprint", &hex); !e.empty()) return fail(e);
    const auto r = std::from_chars(hex.data(), hex.data() + hex.size(), out.learnt_fingerprint, 16);
    if (r.ec != std::errc() || r.ptr != hex.data() + hex.size()) {
      return fail("learnt_fingerprint: not hexadecimal");
    }
    for (const StateField& field : kLearntFields) {
      if (std::string e = read_table_field(in, field, &out.snapshot); !e.empty()) return fail(e);
    }
    for (const StateField& field : kAnchorFields) {
      if (!anchors_saved) break;
      if (std::string e = read_table_field(in, field, &out.snapshot); !e.empty()) return fail(e);
    }
    for (const StateField& field : kTyreFields) {
      if (!tyres_saved) break;
      if (std::string e = read_table_field(in, field, &out.snapshot); !e.empty()) return fail(e);
    }
    if (!tyres_saved) out.snapshot.learnt.evidence_since_tyres = out.snapshot.learnt.evidence;
  }
  if (out.snapshot.gear_masses_saved) {
    if (std::string e = read_gear_masses(in, &out.snapshot.gear_masses); !e.empty()) return fail(e);
  }
  if (version >= kVersionWithoutTyreWatch) {
    if (std::string e = read_pair_terms(in, &out.snapshot); !e.empty()) return fail(e);
  }
  if (version >= kVersion) {
    if (std::string e = read_tyre_watch(in, &out.snapshot.tyre_watch); !e.empty()) return fail(e);
  }
  *state = out;
  return true;
}

bool save_state_file(const std::string& path, const SavedState& state, std::string* error) {
  const std::string text = format_state(state);
  const std::string tmp = path + ".tmp";
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  // Whatever was left at <path>.tmp (a torn write, a FIFO, a symlink) is removed first, and
  // O_EXCL | O_NOFOLLOW create a fresh regular file: the write can neither block nor be
  // redirected.
  ::unlink(tmp.c_str());
  const int fd =
      ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK, 0644);
  if (fd < 0) return fail(errno_text("cannot create", tmp));
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string message = errno_text("write failed", tmp);
      ::close(fd);
      ::unlink(tmp.c_str());
      return fail(message);
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const std::string message = errno_text("fsync failed", tmp);
    ::close(fd);
    ::unlink(tmp.c_str());
    return fail(message);
  }
  if (::close(fd) != 0) {
    const std::string message = errno_text("close failed", tmp);
    ::unlink(tmp.c_str());
    return fail(message);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string message = errno_text("rename failed", path);
    ::unlink(tmp.c_str());
    return fail(message);
  }
  // Make the rename itself durable.
  const std::size_t slash = path.find_last_of('/');
  const std::string dir =
      slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
  return true;
}

StateLoad load_state_file(const std::string& path, std::uint64_t expected_fingerprint,
                          std::optional<std::uint64_t> expected_learnt_fingerprint) {
  StateLoad out;
  // A regular file only, opened without blocking: a FIFO or device at the path is refused.
  const io::FileText text = io::read_regular_file(path, io::kMaxStateBytes, "state file");
  if (!text.ok()) {
    out.status = text.missing ? StateLoadStatus::kMissing : StateLoadStatus::kRejected;
    out.error = text.error;
    return out;
  }
  std::string error;
  if (!parse_state(text.text, &out.state, &error)) {
    out.status = StateLoadStatus::kRejected;
    out.error = path + ": " + error;
    return out;
  }
  SavedState& saved = out.state;
  if (expected_learnt_fingerprint && saved.snapshot.learnt_saved &&
      saved.learnt_fingerprint != *expected_learnt_fingerprint) {
    saved.snapshot.learnt_saved = false;
    saved.snapshot.gear_masses_saved = false;
    saved.snapshot.tyre_watch = TyreWatchState{};
    out.learnt_dropped = path +
                         ": what was learnt about the car was learnt with another rolling "
                         "radius, driveline or resistances; it is forgotten";
  }
  if (saved.fingerprint != expected_fingerprint) {
    out.status = StateLoadStatus::kRejected;
    out.error = path + ": saved for other vehicle, suspension or estimator parameters";
    out.learnt_kept = expected_learnt_fingerprint && saved.snapshot.learnt_saved;
    return out;
  }
  out.status = StateLoadStatus::kLoaded;
  return out;
}

}  // namespace vmass::service
