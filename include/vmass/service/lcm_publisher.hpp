// LcmPublisher: the daemon's LCM output (package vmass, see lcmtypes/*.lcm):
//   VMASS_ESTIMATE  vmass.mass_estimate_t  every tick, or every estimate_decimation-th tick
//   VMASS_STATUS    vmass.status_t         every status_period_s (the caller times it)
//   VMASS_PAIRS     vmass.pair_t           one per tick and block, only when publish_pairs
// Channel names and the URL come from the `lcm:` config section (or --lcm-url).
//
// The to_lcm() conversions are pure and separately testable. Messages are encoded into a
// buffer reserved at construction and published with lcm::LCM::publish(channel, data, size), so
// steady-state publishing does not allocate in our code (LCM's UDP provider may).
//
// Thread-safety: one thread publishes through an LcmPublisher (LCM serialises publishing per
// lcm::LCM instance, but the message objects and buffer here are not shared-safe).
#pragma once

#include <array>

#include <cstdint>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>
#include <vmass/mass_estimate_t.hpp>
#include <vmass/pair_t.hpp>
#include <vmass/status_t.hpp>

#include "vmass/runtime/input_source.hpp"
#include "vmass/runtime/tick_step.hpp"
#include "vmass/scoring/verdict_tally.hpp"
#include "vmass/service/service_config.hpp"
#include "vmass/service/tick_stats.hpp"

namespace vmass::service {

/// Daemon state in status_t.state.
enum class DaemonState : std::uint8_t {
  kStarting = 0,
  kRunning = 1,
  kInputLost = 2,
  kInputEnded = 3,
  kStopping = 4,
};
std::string_view daemon_state_name(DaemonState s);

/// Everything status_t reports, gathered by the publisher thread.
/// The layout of vmass_mass_estimate_t and vmass_status_t (their schema_version field).
constexpr std::int32_t kLcmSchemaVersion = 8;

/// Health counters of one estimator input (status_t's per-input arrays).
struct InputHealth {
  std::int64_t stale = 0, invalid = 0, implausible = 0, counter_fail = 0, checksum_fail = 0;
  std::string reason;  ///< why it is invalid now, "" when valid
};

/// Health of one mapped CAN message (status_t's per-message arrays).
struct MessageHealth {
  std::string name;
  bool valid = true;
  std::int64_t counter_fail = 0, checksum_fail = 0, too_fast = 0, too_long = 0;
};

struct DaemonStatus {
  DaemonState state = DaemonState::kStarting;
  std::string source;
  std::string detail;
  double uptime_s = 0.0;
  double tick_rate_hz = 0.0;
  runtime::TickRecord last;  ///< latest tick (time, estimate, input ages)
  bool has_tick = false;
  std::int64_t frames_received = 0, frames_decoded = 0, frames_unknown = 0, frames_malformed = 0,
               frames_dropped = 0, bus_errors = 0, source_reopens = 0;
  TickTimingSummary timing;
  std::int64_t publish_queue_drops = 0;
  std::int64_t publish_failures = 0;
  std::int64_t state_saves = 0;
  bool state_restored = false;
  // Schema 2 (the driveline lag and the noise come from last.estimate).
  std::array<InputHealth, kInputCount> inputs{};
  std::vector<MessageHealth> messages;
  bool bus_valid = true;
  std::int64_t frames_reordered = 0, frames_late_dropped = 0, time_jumps = 0;
  // Schema 3 (the learnt scale and the known mass come from last.estimate).
  scoring::VerdictTally verdicts;  ///< every block's verdict at every tick since start
  std::int64_t commands_received = 0;
  std::int64_t last_command_utime = 0;  ///< 0: none yet
  std::string last_command_result;
};

/// Reads a source's counters into *status.
void copy_counters(const runtime::SourceCounters& counters, DaemonStatus* status);

/// Conversions (allocate only when a string field grows past its reserved capacity).
void to_lcm(const runtime::TickRecord& record, std::string_view estimator,
            vmass::mass_estimate_t* out);
void to_lcm(const PairEvent& event, Block block, TimeUs tick_us, vmass::pair_t* out);
void to_lcm(const DaemonStatus& status, vmass::status_t* out);

class LcmPublisher {
 public:
  LcmPublisher(lcm::LCM& lcm, const LcmSettings& settings, std::string estimator_name);

  /// Publishes the record's estimate (subject to decimation) and its pairs (when enabled).
  /// Returns false when a publish failed.
  bool on_tick(const runtime::TickRecord& record);
  bool publish_status(const DaemonStatus& status);

  std::int64_t estimates_published() const { return estimates_; }
  const std::string& url() const { return settings_.url; }
  std::int64_t publish_failures() const { return failures_; }

 private:
  template <class Msg>
  bool publish(const std::string& channel, const Msg& msg);

  lcm::LCM& lcm_;
  LcmSettings settings_;
  std::string estimator_;
  vmass::mass_estimate_t estimate_msg_;
  vmass::pair_t pair_msg_;
  vmass::status_t status_msg_;
  std::vector<std::uint8_t> buffer_;
  std::int64_t estimates_ = 0;
  std::int64_t failures_ = 0;
  std::int64_t decimation_count_ = 0;
};

}  // namespace vmass::service
