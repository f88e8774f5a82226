#include "vmass/service/state_store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

namespace vmass::service {
namespace {

constexpr const char* kMagic = "vmass-state";
constexpr int kVersion = 1;

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

void put_int(std::string* out, const char* key, long long v) {
  *out += key;
  *out += ' ';
  *out += std::to_string(v);
  *out += '\n';
}

std::string errno_text(const std::string& what, const std::string& path) {
  return path + ": " + what + ": " + std::strerror(errno);
}

}  // namespace

std::uint64_t state_fingerprint(const PipelineParams& p) {
  const VehicleParams& v = p.vehicle;
  const SuspensionParams& s = p.suspension;
  std::string text = std::string(regressor_type_name(p.estimator.type));
  for (double x : {v.empty_mass_kg, v.wheelbase_m, v.cg_to_front_axle_m, v.gravity_mps2,
                   s.stiffness_n_per_m, s.empty_deflection_m, s.progressive_knee_m,
                   s.progressive_rate_n_per_m2, s.linear_range_kg, s.calibrated_range_kg}) {
    put(&text, "x", x);
  }
  return fnv1a(text.data(), text.size());
}

std::string format_state(const SavedState& state) {
  const PipelineSnapshot& s = state.snapshot;
  std::string out;
  out += std::string(kMagic) + " " + std::to_string(kVersion) + "\n";
  char hex[32];
  std::snprintf(hex, sizeof hex, "%016" PRIx64, state.fingerprint);
  out += std::string("fingerprint ") + hex + "\n";
  put_int(&out, "saved_time_us", state.saved_time_us);
  out += std::string("type ") + std::string(regressor_type_name(s.type)) + "\n";
  put_int(&out, "has_prior", s.has_prior ? 1 : 0);
  put_int(&out, "prior_reason", static_cast<int>(s.prior_reason));
  put(&out, "prior_mass_kg", s.prior.mass_kg);
  put(&out, "prior_mass_std_kg", s.prior.mass_std_kg);
  put(&out, "prior_mu_n", s.prior.mu_n);
  put(&out, "prior_mu_std_n", s.prior.mu_std_n);
  put_int(&out, "pairs_used", s.pairs_used);
  put(&out, "rls_theta_0", s.rls_theta[0]);
  put(&out, "rls_theta_1", s.rls_theta[1]);
  for (int i = 0; i < 4; ++i) {
    put(&out, ("rls_covariance_" + std::to_string(i)).c_str(), s.rls_covariance[i]);
  }
  put(&out, "nig_mean_0", s.nig_mean[0]);
  put(&out, "nig_mean_1", s.nig_mean[1]);
  for (int i = 0; i < 4; ++i) {
    put(&out, ("nig_scaled_covariance_" + std::to_string(i)).c_str(), s.nig_scaled_covariance[i]);
  }
  put(&out, "nig_shape", s.nig_shape);
  put(&out, "nig_scale", s.nig_scale);
  put_int(&out, "has_reference", s.has_reference ? 1 : 0);
  put(&out, "reference_deflection_m", s.reference_deflection_m);
  put(&out, "reference_deflection_std_m", s.reference_deflection_std_m);
  put(&out, "reference_grade_accel_mps2", s.reference_grade_accel_mps2);  // may be nan
  for (int b = 0; b < kBlockCount; ++b) {
    const std::string prefix = std::string(block_name(static_cast<Block>(b))) + "_";
    const BlockCounters& c = s.blocks[static_cast<std::size_t>(b)];
    put_int(&out, (prefix + "ticks").c_str(), c.ticks);
    put_int(&out, (prefix + "candidates").c_str(), c.candidates);
    put_int(&out, (prefix + "accepted").c_str(), c.accepted);
    put_int(&out, (prefix + "rejected_innovation").c_str(), c.rejected_innovation);
  }
  std::snprintf(hex, sizeof hex, "%016" PRIx64, fnv1a(out.data(), out.size()));
  out += std::string("checksum ") + hex + "\n";
  return out;
}

// NOLINTNEXTLINE(readability-function-size): not split yet (issue 9)
bool parse_state(const std::string& text, SavedState* state, std::string* error) {
  auto fail = [&](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  const std::size_t checksum_at = text.rfind("checksum ");
  if (checksum_at == std::string::npos || (checksum_at > 0 && text[checksum_at - 1] != '\n')) {
    return fail("no checksum line (truncated file?)");
  }
  {
    std::uint64_t expected = 0;
    const char* begin = text.data() + checksum_at + 9;
    const char* end = text.data() + text.size();
    while (end > begin && (end[-1] == '\n' || end[-1] == '\r')) --end;
    const auto r = std::from_chars(begin, end, expected, 16);
    if (r.ec != std::errc() || r.ptr != end) return fail("malformed checksum line");
    if (fnv1a(text.data(), checksum_at) != expected)
      return fail("checksum mismatch (corrupt file)");
  }
  std::map<std::string, std::string> values;
  std::istringstream in(text.substr(0, checksum_at));
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::size_t space = line.find(' ');
    if (space == std::string::npos) {
      return fail("line " + std::to_string(line_no) + ": expected 'key value'");
    }
    values[line.substr(0, space)] = line.substr(space + 1);
  }
  if (values[kMagic] != std::to_string(kVersion)) {
    return fail("not a vmass state file of format version " + std::to_string(kVersion));
  }
  auto get_text = [&](const char* key, std::string* out) {
    const auto it = values.find(key);
    if (it == values.end()) return fail(std::string("missing key ") + key);
    *out = it->second;
    return true;
  };
  auto get_double = [&](const std::string& key, double* out) {
    std::string v;
    if (!get_text(key.c_str(), &v)) return false;
    const auto r = std::from_chars(v.data(), v.data() + v.size(), *out);
    if (r.ec != std::errc() || r.ptr != v.data() + v.size()) {
      // from_chars does not read "inf"/"nan" spellings of every libc; they are invalid here.
      return fail(key + ": not a number: '" + v + "'");
    }
    return true;
  };
  auto get_long = [&](const std::string& key, long long* out) {
    std::string v;
    if (!get_text(key.c_str(), &v)) return false;
    const auto r = std::from_chars(v.data(), v.data() + v.size(), *out);
    if (r.ec != std::errc() || r.ptr != v.data() + v.size()) {
      return fail(key + ": not an integer: '" + v + "'");
    }
    return true;
  };

  SavedState out;
  PipelineSnapshot& s = out.snapshot;
  std::string fingerprint, type;
  long long n = 0;
  if (!get_text("fingerprint", &fingerprint)) return false;
  {
    const auto r = std::from_chars(fingerprint.data(), fingerprint.data() + fingerprint.size(),
                                   out.fingerprint, 16);
    if (r.ec != std::errc()) return fail("fingerprint: not hexadecimal");
  }
  if (!get_long("saved_time_us", &n)) return false;
  out.saved_time_us = n;
  if (!get_text("type", &type)) return false;
  if (type == "rls") {
    s.type = RegressorType::kRls;
  } else if (type == "bayes") {
    s.type = RegressorType::kBayes;
  } else {
    return fail("type: expected rls or bayes, got '" + type + "'");
  }
  if (!get_long("has_prior", &n)) return false;
  s.has_prior = n != 0;
  if (!get_long("prior_reason", &n)) return false;
  if (n < 0 || n > static_cast<long long>(StatusReason::kRestored)) {
    return fail("prior_reason: out of range");
  }
  s.prior_reason = static_cast<StatusReason>(n);
  if (!get_double("prior_mass_kg", &s.prior.mass_kg) ||
      !get_double("prior_mass_std_kg", &s.prior.mass_std_kg) ||
      !get_double("prior_mu_n", &s.prior.mu_n) ||
      !get_double("prior_mu_std_n", &s.prior.mu_std_n)) {
    return false;
  }
  if (!get_long("pairs_used", &n)) return false;
  s.pairs_used = static_cast<long>(n);
  if (!get_double("rls_theta_0", &s.rls_theta[0]) || !get_double("rls_theta_1", &s.rls_theta[1])) {
    return false;
  }
  for (int i = 0; i < 4; ++i) {
    if (!get_double("rls_covariance_" + std::to_string(i), &s.rls_covariance[i])) return false;
  }
  if (!get_double("nig_mean_0", &s.nig_mean[0]) || !get_double("nig_mean_1", &s.nig_mean[1])) {
    return false;
  }
  for (int i = 0; i < 4; ++i) {
    if (!get_double("nig_scaled_covariance_" + std::to_string(i), &s.nig_scaled_covariance[i])) {
      return false;
    }
  }
  if (!get_double("nig_shape", &s.nig_shape) || !get_double("nig_scale", &s.nig_scale)) {
    return false;
  }
  if (!get_long("has_reference", &n)) return false;
  s.has_reference = n != 0;
  if (!get_double("reference_deflection_m", &s.reference_deflection_m) ||
      !get_double("reference_deflection_std_m", &s.reference_deflection_std_m)) {
    return false;
  }
  // Optional (files from before the grade check): NaN = unknown grade.
  s.reference_grade_accel_mps2 = std::numeric_limits<double>::quiet_NaN();
  if (values.count("reference_grade_accel_mps2") != 0) {
    const std::string& v = values["reference_grade_accel_mps2"];
    if (v != "nan" && v != "-nan" &&
        !get_double("reference_grade_accel_mps2", &s.reference_grade_accel_mps2)) {
      return false;
    }
  }
  for (int b = 0; b < kBlockCount; ++b) {
    const std::string prefix = std::string(block_name(static_cast<Block>(b))) + "_";
    BlockCounters& c = s.blocks[static_cast<std::size_t>(b)];
    long long ticks = 0, candidates = 0, accepted = 0, rejected = 0;
    if (!get_long(prefix + "ticks", &ticks) || !get_long(prefix + "candidates", &candidates) ||
        !get_long(prefix + "accepted", &accepted) ||
        !get_long(prefix + "rejected_innovation", &rejected)) {
      return false;
    }
    c.ticks = static_cast<long>(ticks);
    c.candidates = static_cast<long>(candidates);
    c.accepted = static_cast<long>(accepted);
    c.rejected_innovation = static_cast<long>(rejected);
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
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
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

StateLoad load_state_file(const std::string& path, std::uint64_t expected_fingerprint) {
  StateLoad out;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (::access(path.c_str(), F_OK) != 0) {
      out.status = StateLoadStatus::kMissing;
    } else {
      out.status = StateLoadStatus::kRejected;
      out.error = path + ": cannot read";
    }
    return out;
  }
  std::ostringstream text;
  text << in.rdbuf();
  std::string error;
  if (!parse_state(text.str(), &out.state, &error)) {
    out.status = StateLoadStatus::kRejected;
    out.error = path + ": " + error;
    return out;
  }
  if (out.state.fingerprint != expected_fingerprint) {
    out.status = StateLoadStatus::kRejected;
    out.error = path + ": saved for other vehicle, suspension or estimator parameters";
    return out;
  }
  out.status = StateLoadStatus::kLoaded;
  return out;
}

}  // namespace vmass::service
