// ServiceConfig: the daemon's own sections of the config file, `lcm:` and `daemon:`, parsed
// from the raw YAML that load_config() keeps (Config::lcm, Config::daemon). Errors name the
// file, the line and the key; unknown keys are errors. Keys and defaults:
//
//   lcm:
//     url: "udpm://239.255.76.67:7667?ttl=0"   # LCM provider URL (--lcm-url overrides)
//     estimate_channel: VMASS_ESTIMATE
//     status_channel: VMASS_STATUS
//     pairs_channel: VMASS_PAIRS
//     command_channel: VMASS_COMMAND  # vmass.command_t to the daemon (vmass-ctl)
//     estimate_decimation: 1        # publish every n-th tick's estimate (1 = every tick)
//     status_period_s: 1.0          # VMASS_STATUS period, s
//     publish_pairs: false          # debug channel: one vmass.pair_t per tick and block
//   daemon:
//     can_interface: can0           # SocketCAN interface when neither --can nor a replay is given
//     state_file: ""                # "" = $STATE_DIRECTORY/vmassd.state under systemd, else none
//     persist_interval_s: 30.0      # how often the state is saved while running (and at exit)
//     input_timeout_s: 0            # samples input: a value older than this is stale;
//                                   #   0 = 5 ticks (5 / estimator.tick_rate_hz, as vmass-replay)
//     publish_queue: 1024           # estimator -> publisher ring capacity, records
//     receive_period_ms: 10         # a live bus is read this often, phase-locked to the ticks
//                                   #   (0 = at every frame's arrival; <= 100)
//     realtime:
//       priority: 0                 # SCHED_FIFO priority of the estimator thread, 1..99; 0 = off
//       cpu_affinity: []            # CPUs the estimator thread may run on ([] = any)
//       lock_memory: false          # mlockall(MCL_CURRENT | MCL_FUTURE)
//
// Configuration time only (allocates, uses yaml-cpp). Not thread-safe.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "vmass/config/config.hpp"
#include "vmass/config/field_table.hpp"

namespace vmass::service {

struct LcmSettings {
  std::string url = "udpm://239.255.76.67:7667?ttl=0";
  std::string estimate_channel = "VMASS_ESTIMATE";
  std::string status_channel = "VMASS_STATUS";
  std::string pairs_channel = "VMASS_PAIRS";
  std::string command_channel = "VMASS_COMMAND";
  int estimate_decimation = 1;
  double status_period_s = 1.0;
  bool publish_pairs = false;

  /// "" or "lcm.key: message".
  std::string validate() const;
};

struct RealtimeSettings {
  int priority = 0;
  std::vector<int> cpu_affinity;
  bool lock_memory = false;

  std::string validate() const;
};

struct DaemonSettings {
  std::string can_interface = "can0";
  std::string state_file;
  double persist_interval_s = 30.0;
  double input_timeout_s = 0.0;  ///< 0: 5 ticks
  int publish_queue = 1024;
  /// A live socket is drained once per this period (a divisor of the tick period, one drain
  /// just before each tick): the frames wait in the kernel with their kernel time stamps, so
  /// the estimates do not change, and the receive thread wakes ~100 times a second instead of
  /// at every burst of frames. 0: read as frames arrive.
  double receive_period_ms = 10.0;
  RealtimeSettings realtime;

  std::string validate() const;
};

inline constexpr std::array<Field<LcmSettings>, 8> kLcmFields{{
    {"url", &LcmSettings::url},
    {"estimate_channel", &LcmSettings::estimate_channel},
    {"status_channel", &LcmSettings::status_channel},
    {"pairs_channel", &LcmSettings::pairs_channel},
    {"command_channel", &LcmSettings::command_channel},
    {"estimate_decimation", &LcmSettings::estimate_decimation},
    {"status_period_s", &LcmSettings::status_period_s},
    {"publish_pairs", &LcmSettings::publish_pairs},
}};

inline constexpr std::array<Field<DaemonSettings>, 6> kDaemonFields{{
    {"can_interface", &DaemonSettings::can_interface},
    {"state_file", &DaemonSettings::state_file},
    {"persist_interval_s", &DaemonSettings::persist_interval_s},
    {"input_timeout_s", &DaemonSettings::input_timeout_s},
    {"publish_queue", &DaemonSettings::publish_queue},
    {"receive_period_ms", &DaemonSettings::receive_period_ms},
}};

/// `daemon.realtime:`
inline constexpr std::array<Field<RealtimeSettings>, 3> kRealtimeFields{{
    {"priority", &RealtimeSettings::priority},
    {"cpu_affinity", &RealtimeSettings::cpu_affinity},
    {"lock_memory", &RealtimeSettings::lock_memory},
}};

struct ServiceSettings {
  LcmSettings lcm;
  DaemonSettings daemon;
  std::string dbc_path;  ///< `can.dbc` resolved against the config file ("" when absent)
};

struct ServiceSettingsLoad {
  ServiceSettings settings;
  std::string error;  ///< "file:line: key: message" or ""
  bool ok() const { return error.empty(); }
};

/// Parses config.lcm and config.daemon through the tables above (and reads can.dbc; the rest of
/// `can:` belongs to the CAN signal mapping and is not checked here). vmassd and vmass-replay
/// both check them, so that a config one accepts the other does not refuse.
ServiceSettingsLoad load_service_settings(const Config& config);

}  // namespace vmass::service
