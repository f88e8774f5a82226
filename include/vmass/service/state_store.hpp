// StateStore: the daemon's saved estimate (persistence across restarts): a PipelineSnapshot plus
// when it was saved and a fingerprint of the parameters it is valid for.
//
// File format: UTF-8 text, one `key value` per line, numbers locale-free with 17 significant
// digits (doubles round-trip exactly), ending in `checksum <FNV-1a 64 of every byte before that
// line, hex>`. A file with a wrong checksum, a missing key, another format version or another
// fingerprint is refused with a message; nothing is restored from it.
//
// Writing is atomic: the text goes to `<path>.tmp`, which is fsync'ed and renamed over `path`,
// then the directory is fsync'ed. A crash (SIGKILL, power loss after the rename's journal commit)
// leaves either the old file or the new one, never a torn one.
//
// The fingerprint covers what makes a saved belief about "this vehicle": the regressor type, the
// vehicle's empty mass, geometry and gravity, and the suspension calibration (eq. 3). Changing
// any of them in the config discards the saved state.
//
// Thread-safety: free functions, reentrant; save and load of the same path must not overlap.
// They allocate and do I/O: never call them from the estimator thread.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "vmass/core/pipeline.hpp"

namespace vmass::service {

struct SavedState {
  PipelineSnapshot snapshot;
  TimeUs saved_time_us = 0;       ///< time of the tick the snapshot was taken at (input clock)
  std::uint64_t fingerprint = 0;  ///< state_fingerprint() of the parameters
  std::uint64_t learnt_fingerprint = 0;  ///< learnt_fingerprint() of the parameters
};

std::uint64_t state_fingerprint(const PipelineParams& params);
/// What the learnt section is relative to: the constants the lumped scale multiplies (the
/// rolling radius, the driveline's ratios and efficiency, the pitch gradient, the rotating
/// masses, the brake gain, the resistances). A config that changes one of them makes what was
/// learnt wrong: it is dropped, and the mass section is kept if its own fingerprint holds. The
/// mass section's fingerprint does not cover the learnt section: another estimator type or
/// suspension calibration keeps what was learnt about the car.
std::uint64_t learnt_fingerprint(const PipelineParams& params);

std::string format_state(const SavedState& state);
/// Parses format_state()'s text; false and *error ("line N: ...") when it is not valid.
bool parse_state(const std::string& text, SavedState* state, std::string* error);

/// Writes atomically (see the header comment). false and *error on any I/O failure; the
/// previous file is then untouched.
bool save_state_file(const std::string& path, const SavedState& state, std::string* error);

enum class StateLoadStatus : std::uint8_t {
  kLoaded,    ///< *state holds a valid saved state for these parameters
  kMissing,   ///< no file: a first start
  kRejected,  ///< unreadable, corrupt, or for other parameters (see error)
};

struct StateLoad {
  StateLoadStatus status = StateLoadStatus::kMissing;
  SavedState state;
  std::string error;
  /// kRejected for the mass section's fingerprint only: the learnt section, which still fits.
  bool learnt_kept = false;
  /// The learnt section was dropped (its fingerprint differs): why; "" when it was not.
  std::string learnt_dropped;
};

/// Reads and checks a state file against the fingerprints of the current parameters (the
/// learnt section's only when expected_learnt_fingerprint is given).
StateLoad load_state_file(const std::string& path, std::uint64_t expected_fingerprint,
                          std::optional<std::uint64_t> expected_learnt_fingerprint = {});

}  // namespace vmass::service
