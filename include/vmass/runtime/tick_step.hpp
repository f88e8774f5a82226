// TickStep: what happens at each tick, in vmass-replay and in the daemon's estimator thread:
//
//   InputSource's table --sample_at(T)--> Sample --Pipeline::step--> TickRecord
//
// The tick time T is the caller's: T_k on the TickGrid, in the input's clock (the log time of a
// recording, CLOCK_REALTIME for a live bus), so the pipeline always sees the regular grid it
// differences on, whatever the wake-up jitter. A TickRecord carries everything the
// publisher needs (estimate, diagnostic pairs, input ages) as plain values for the SPSC queue.
//
// Not thread-safe (one thread ticks). tick() allocates nothing.
#pragma once

#include <array>
#include <cstdint>

#include "vmass/core/pipeline.hpp"
#include "vmass/runtime/input_source.hpp"

namespace vmass::runtime {

/// One tick's outcome (trivially copyable: goes through SpscQueue).
struct TickRecord {
  std::int64_t tick = 0;  ///< tick index since start
  Estimate estimate;
  std::array<PairEvent, kBlockCount> events{};
  bool estimate_changed = false;
  InputMask inputs_valid = 0;            ///< validity of each input at this tick
  double input_age_s[kInputCount] = {};  ///< T - time of the input's last update; -1: never
};

class TickStep {
 public:
  /// params must be valid.
  explicit TickStep(const PipelineParams& params);

  /// Runs tick number `tick` at time tick_us on the source's table (estimator thread: see
  /// InputSource): the Sample, the pipeline step, and each input's age and validity.
  const TickRecord& tick(std::int64_t tick, TimeUs tick_us, InputSource& source);

  /// The pipeline's state, to save (Pipeline::snapshot()).
  PipelineSnapshot snapshot() const { return pipeline_.snapshot(); }
  /// Resumes from a saved state (Pipeline::restore()); false: refused, nothing changed.
  bool restore(const PipelineSnapshot& snapshot) { return pipeline_.restore(snapshot); }
  /// Resumes what was learnt alone (Pipeline::restore_learnt()).
  bool restore_learnt(const PipelineSnapshot& snapshot) {
    return pipeline_.restore_learnt(snapshot);
  }
  /// The user's known mass of the current load (Pipeline::declare_known_mass()).
  bool declare_known_mass(double mass_kg, double std_kg) {
    return pipeline_.declare_known_mass(mass_kg, std_kg);
  }
  /// Forget what was learnt about the car (Pipeline::reset_learnt()).
  void reset_learnt() { pipeline_.reset_learnt(); }
  /// New tyres were fitted (Pipeline::tyres_changed()).
  void tyres_changed() { pipeline_.tyres_changed(); }
  /// At the end of the input: takes the open batch in (Pipeline::flush()); true when the
  /// estimate changed.
  bool flush() { return pipeline_.flush(); }

  const Pipeline& pipeline() const { return pipeline_; }
  const TickRecord& last() const { return record_; }

 private:
  Pipeline pipeline_;
  TickRecord record_;
};

}  // namespace vmass::runtime
