// The daemon: vmassd's threads around the ticking front end (vmass_runtime), LCM publishing,
// state persistence and systemd; tools/vmassd/main.cpp only parses the command line.
//
//   receive thread    runtime::InputSource::next_record/copy_record -> SpscQueue<InputRecord>
//                     (a live bus: frames re-stamped into the tick clock, dropped and counted
//                     when the queue is full; a recording: paced by its log time / speed, never
//                     dropped)
//   estimator thread  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME) at tick_rate * speed;
//                     drains the input queue into the source's table (SignalTable::on_frame for
//                     CAN), sample_at + Pipeline::step; TickRecord -> SpscQueue; overruns counted
//   publisher thread  SpscQueue -> LCM (VMASS_ESTIMATE, VMASS_PAIRS); VMASS_STATUS periodically
//   main thread       signals (sigtimedwait), sd_notify READY/STATUS/WATCHDOG/STOPPING, state
//                     persistence, orderly shutdown (final status; the pipeline flushed, so
//                     that an open Bayes batch is not lost, then the final save)
//
// The input table (SignalTable) belongs to the estimator thread alone; only records (frames)
// cross threads, through the SPSC ring, so nothing of the table is shared or locked.
//
// With `--speed max` there is no receive thread: the estimator thread plays the recording
// through runtime::TickDriver, the loop vmass-replay runs (log time on runtime::TickGrid, every
// record stamped <= T_k applied before tick k, runtime::TickStep), so both give bit-identical
// estimates by construction. At a
// finite speed tick k applies the records stamped <= T_k (later ones wait for their tick) and
// waits, when the receive thread lags, until all of them are in the ring (a replay skips no
// tick; one the machine cannot keep up with runs late): a replay at any speed gives the offline
// estimates too, all of them: for a recording the publisher SPSC queue applies back-pressure
// instead of dropping (a live bus's estimates are dropped, counted, when it is full).
//
// After start-up the estimator thread allocates nothing (fixed-size records, SPSC rings,
// seqlocks, the SignalTable's preallocated terms); the receive thread allocates only in the file
// readers (samples CSV, candump lines).
#pragma once

#include <string>

namespace vmass::service {

struct DaemonOptions {
  std::string config_path;
  std::string can_interface;  ///< --can
  /// --can-fd: SocketCAN records (struct can_frame / canfd_frame) from this inherited
  /// descriptor instead of an interface, through the reader's fd seam (benchmarks, tests); -1:
  /// none.
  int can_fd = -1;
  std::string replay_log;   ///< --replay (a CAN log: runtime/log_frame_source.hpp)
  std::string samples_csv;  ///< --samples
  std::string speed = "1";  ///< --speed X|max (recordings only)
  std::string lcm_url;      ///< --lcm-url (overrides lcm.url)
  std::string state_file;   ///< --state-file (overrides daemon.state_file)
  bool no_restore = false;  ///< --no-restore
};

/// Runs the daemon until SIGTERM/SIGINT or the end of a recording. Returns the process exit
/// code (tools/common/exit_code.hpp): 0 orderly stop, 1 start-up failure (SocketCAN or LCM
/// cannot be opened), 2 usage, configuration or input error.
int run_daemon(const DaemonOptions& options);

}  // namespace vmass::service
