// The daemon: vmassd's threads around the ticking front end (vmass_runtime), LCM publishing,
// state persistence and systemd; tools/vmassd/main.cpp only parses the command line.
//
//   receive thread    runtime::InputSource::next_record/copy_record -> runtime::RecordRing
//                     (a live bus: frames re-stamped into the tick clock, dropped and counted
//                     when the ring is full; a recording: paced by its log time / speed, never
//                     dropped)
//   estimator thread  runtime::TickDriver, the tick loop every front end runs, fed from the
//                     ring (runtime::RingFeed) on a clock_nanosleep(CLOCK_MONOTONIC,
//                     TIMER_ABSTIME) clock at tick_rate * speed: the records into the source's
//                     table (SignalTable::on_frame for CAN), runtime::TickStep (sample_at +
//                     Pipeline::step); TickRecord -> SpscQueue; overruns counted
//   publisher thread  SpscQueue -> LCM (VMASS_ESTIMATE, VMASS_PAIRS); VMASS_STATUS periodically
//   main thread       signals (sigtimedwait), sd_notify READY/STATUS/WATCHDOG/STOPPING, state
//                     persistence, orderly shutdown (final status; the pipeline flushed, so
//                     that an open Bayes batch is not lost, then the final save)
//
// The input table (SignalTable) belongs to the estimator thread alone; only records (frames)
// cross threads, through the SPSC ring, so nothing of the table is shared or locked.
//
// Every pace runs the same runtime::TickDriver, the loop vmass-replay runs (log time on
// runtime::TickGrid, every record stamped <= T_k applied before tick k), so a replay gives the
// offline estimates by construction. With `--speed max` there is no receive thread: the
// driver reads the recording itself, every tick at once. At a finite speed tick k waits, when
// the receive thread lags, until every record stamped <= T_k is in the ring (a replay skips no
// tick; one the machine cannot keep up with runs late); for a recording the publisher SPSC
// queue applies back-pressure instead of dropping (a live bus's estimates are dropped, counted,
// when it is full, and a live clock gives ticks missed by more than 1 s up, counted).
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
  std::string replay_log;  ///< --replay (a CAN log: runtime/log_frame_source.hpp)
  /// --interface: the one interface of the --replay log to read ("": all of them)
  std::string replay_interface;
  std::string samples_csv;  ///< --samples
  std::string speed = "1";  ///< --speed X|max (recordings only)
  std::string lcm_url;      ///< --lcm-url (overrides lcm.url)
  std::string state_file;   ///< --state-file (overrides daemon.state_file)
  bool no_restore = false;  ///< --no-restore
};

/// Runs the daemon until SIGTERM/SIGINT or the end of a recording. Returns the process exit
/// code (tools/common/exit_code.hpp): 0 orderly stop, 1 start-up failure (SocketCAN or LCM
/// cannot be opened), 2 usage, configuration or input error (a replay that ended without a
/// frame on its --interface too).
int run_daemon(const DaemonOptions& options);

}  // namespace vmass::service
