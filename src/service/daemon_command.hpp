// vmassd's commands (VMASS_COMMAND, vmass.command_t; vmass-ctl): the command thread receives
// and checks them, the estimator thread applies them to its pipeline at its next tick and says
// what it did in the status (last_command_utime, last_command_result). Private to vmass_service.
//
// Thread-safety: DaemonCommand and CommandResult are plain values (trivially copyable) for the
// SPSC queue and the seqlock between the two threads.
#pragma once

#include <cstdint>
#include <string>

#include <lcm/lcm-cpp.hpp>

#include "vmass/runtime/tick_step.hpp"

namespace vmass::service::daemon {

struct Shared;

struct DaemonCommand {
  enum class Kind : std::uint8_t { kKnownMass, kResetLearnt, kTyresChanged, kRefused };
  std::int64_t utime = 0;  ///< the command's id (its sender's clock)
  Kind kind = Kind::kRefused;
  double mass_kg = 0.0;
  double std_kg = 0.0;
  char refusal[120] = {};  ///< kRefused: why
};

struct CommandResult {
  std::int64_t utime = 0;  ///< the command's id; 0: no command yet
  char text[160] = {};     ///< "accepted: ..." or "refused: ..."
};

/// Receives vmass.command_t on `channel` until shared.stop_publisher; each one, checked, into
/// shared.commands (a full queue refuses it, logged).
void command_thread(lcm::LCM& lcm, const std::string& channel, Shared& shared);

/// Estimator thread, before a tick: applies the queued commands to `step`'s pipeline and writes
/// each one's result to shared.command_result.
void apply_commands(runtime::TickStep& step, Shared& shared);

}  // namespace vmass::service::daemon
