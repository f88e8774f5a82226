// vmassd's threads (see vmass/service/daemon.hpp for how they work together) and what they
// share. Private to vmass_service.
//
// Thread-safety: Shared is the only state the threads touch together, through its atomics,
// SPSC rings, seqlocks and semaphore; Plan and StatusContext are read-only once the threads run.
#pragma once

#include <semaphore.h>

#include <atomic>
#include <climits>
#include <cstdint>
#include <string>

#include "daemon_command.hpp"
#include "vmass/core/pipeline.hpp"
#include "vmass/runtime/input_source.hpp"
#include "vmass/runtime/record_ring.hpp"
#include "vmass/runtime/seqlock.hpp"
#include "vmass/runtime/spsc_queue.hpp"
#include "vmass/runtime/tick_grid.hpp"
#include "vmass/runtime/tick_step.hpp"
#include "vmass/scoring/verdict_tally.hpp"
#include "vmass/service/lcm_publisher.hpp"
#include "vmass/service/service_config.hpp"
#include "vmass/service/tick_stats.hpp"

namespace vmass::service::daemon {

// receive -> estimator ring, records (~100 B each): 4096 frames are ~1 s of a busy 500 kbit/s
// bus after the kernel's DBC-id filter, many ticks of slack for the estimator thread.
constexpr std::size_t kInputQueueRecords = 4096;
// command -> estimator ring: a person's commands, applied at the next tick.
constexpr std::size_t kCommandQueue = 16;

struct SnapshotSlot {
  vmass::PipelineSnapshot snapshot;
  TimeUs time_us = 0;
  bool valid = false;
};

/// Everything the threads share. Allocated once at start-up.
struct Shared {
  explicit Shared(std::size_t queue_capacity)
      : inputs(kInputQueueRecords), queue(queue_capacity), commands(kCommandQueue) {
    sem_init(&queue_sem, 0, 0);
  }
  ~Shared() { sem_destroy(&queue_sem); }

  std::atomic<bool> stop{false};            ///< main -> receive, estimator
  std::atomic<bool> stop_publisher{false};  ///< main -> publisher (after the estimator joined)
  std::atomic<bool> estimator_done{false};  ///< a recording was played to its end
  /// receive -> estimator (frames, rows); `ended`: the input ended (a recording's end)
  runtime::RecordRing inputs;
  std::atomic<std::int64_t> input_drops{0};       ///< live records the full input ring refused
  runtime::SpscQueue<runtime::TickRecord> queue;  ///< estimator -> publisher
  sem_t queue_sem;
  std::atomic<std::int64_t> queue_drops{0};
  std::atomic<std::int64_t> publish_failures{0};        ///< publisher: messages not published
  std::atomic<std::int64_t> published{0};               ///< publisher: messages published
  std::atomic<std::int64_t> live_clock_steps{0};        ///< receive: live stamps off the tick clock
  runtime::SeqLock<runtime::TickRecord> latest;         ///< estimator -> main, publisher (status)
  runtime::SeqLock<TickTimingSummary> timing;           ///< estimator -> status
  runtime::SeqLock<SnapshotSlot> snapshot;              ///< estimator -> main (persistence)
  runtime::SeqLock<runtime::InputHealthRecord> health;  ///< estimator -> status
  std::atomic<std::int64_t> heartbeat{0};               ///< ticks run (watchdog evidence)
  std::atomic<std::int64_t> state_saves{0};
  std::atomic<std::int64_t> late_records{0};         ///< applied after the tick they belonged to
  runtime::SeqLock<scoring::VerdictTally> verdicts;  ///< estimator -> status: why no pair
  runtime::SpscQueue<DaemonCommand> commands;        ///< command thread -> estimator
  std::atomic<std::int64_t> commands_received{0};
  runtime::SeqLock<CommandResult> command_result;  ///< estimator -> status
};

/// The fixed parameters of a run.
struct Plan {
  bool recorded = false;
  bool max_speed = false;
  double speed = 1.0;
  double tick_rate_hz = 100.0;
  std::int64_t period_ns = 0;  ///< wall-clock period of the loop
  TimeUs t0_us = 0;            ///< time of tick 0 (input clock)
  std::int64_t mono0_ns = 0;   ///< CLOCK_MONOTONIC of tick 0
  bool has_first_record = false;
  int snapshot_every_ticks = 10;
  std::int64_t receive_period_ns = 0;  ///< live drain period (ReceiveSchedule); 0: per frame
  RealtimeSettings realtime;

  /// T_k in the input clock: the grid every front end ticks on (runtime::TickGrid).
  TimeUs tick_time(std::int64_t k) const {
    return runtime::TickGrid(t0_us, tick_rate_hz).time_of(k);
  }
};

struct StatusContext {
  const runtime::InputSource* source = nullptr;
  std::string source_name;
  double tick_rate_hz = 100.0;
  std::int64_t start_mono_ns = 0;
  bool state_restored = false;
};

/// Reads the input and hands its records to the estimator thread (not at `--speed max`): a
/// recording paced by its log time / speed, never dropped; a live bus re-stamped into the tick
/// clock, dropped and counted when the ring is full.
void receive_thread(runtime::InputSource& source, Shared& shared, const Plan& plan);

/// Ticks the pipeline through runtime::TickDriver: in log time at `--speed max`, else at the
/// plan's period on CLOCK_MONOTONIC from the input ring; publishes every TickRecord.
void estimator_thread(runtime::InputSource& source, runtime::TickStep& step, Shared& shared,
                      const Plan& plan);

/// Publishes the estimator's records on LCM, and the status every status_period_s.
void publisher_thread(LcmPublisher& publisher, Shared& shared, const StatusContext& ctx,
                      double status_period_s);

/// The record's counts, reasons (as text), messages and bus validity into *s.
void copy_input_health(const runtime::InputSource& source, const runtime::InputHealthRecord& h,
                       DaemonStatus* s);
DaemonStatus gather_status(const StatusContext& ctx, Shared& shared, bool stopping);
/// One line for systemd's STATUS= and the log.
std::string summary_line(const DaemonStatus& s);
/// Saves the slot's snapshot to `path` ("" = no state file). True when saved.
bool save_snapshot(const std::string& path, const SnapshotSlot& slot, const PipelineParams& params,
                   Shared& shared);

}  // namespace vmass::service::daemon
