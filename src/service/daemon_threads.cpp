#include "daemon_threads.hpp"

#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>

#include <spdlog/spdlog.h>

#include "daemon_clock.hpp"
#include "publish_backoff.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/service/pipeline_state.hpp"
#include "vmass/service/receive_schedule.hpp"
#include "vmass/service/state_store.hpp"

namespace vmass::service::daemon {
namespace {

void apply_realtime(const RealtimeSettings& rt) {
  if (!rt.cpu_affinity.empty()) {
    cpu_set_t set;
    CPU_ZERO(&set);
    for (int cpu : rt.cpu_affinity) CPU_SET(static_cast<unsigned>(cpu), &set);
    const int err = pthread_setaffinity_np(pthread_self(), sizeof set, &set);
    if (err != 0) {
      spdlog::warn(
          "daemon.realtime.cpu_affinity: cannot pin the estimator thread ({}); running "
          "unpinned",
          std::strerror(err));
    }
  }
  if (rt.priority > 0) {
    sched_param param{};
    param.sched_priority = rt.priority;
    const int err = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param);
    if (err != 0) {
      spdlog::warn(
          "daemon.realtime.priority: SCHED_FIFO {} refused ({}); running with normal "
          "scheduling (grant LimitRTPRIO= or CPUSchedulingPolicy=fifo)",
          rt.priority, std::strerror(err));
    }
  }
}

// ----------------------------------------------------------------------------- receive thread

/// Hands a record to the estimator thread. A recording waits for room (back-pressure: nothing of
/// a log is lost); a live bus never waits: the record is dropped and counted.
void push_input(const runtime::InputRecord& record, Shared& shared, bool block) {
  while (!shared.inputs.records.push(record)) {
    if (!block) {
      shared.input_drops.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    if (shared.stop.load(std::memory_order_relaxed)) return;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

/// A live frame's time in the tick clock: its kernel stamp (CLOCK_REALTIME) moved by the tick
/// clock's offset from CLOCK_REALTIME at `now` (read once per drain: the offset does not depend
/// on when it is read; read again for a frame stamped after it, which arrived during the drain).
/// A stamp older than 1 s or in the future means the wall clock was stepped (or the frame has
/// no stamp): then the time it was read. So the inputs' ages and timeouts never depend on
/// CLOCK_REALTIME steps, which are common on a vehicle PC that sets its clock after boot (GNSS,
/// NTP). Such a stamp is counted as a time jump.
TimeUs live_time_us(TimeUs kernel_stamp_us, const Plan& plan, Shared& shared, ClockPair* now) {
  if (now->realtime_us < kernel_stamp_us) *now = read_clocks();
  const TimeUs tick_clock_us = plan.t0_us + (now->mono_ns - plan.mono0_ns) / 1000;
  const TimeUs waited = now->realtime_us - kernel_stamp_us;
  if (waited >= 0 && waited <= 1'000'000) return tick_clock_us - waited;
  shared.live_clock_steps.fetch_add(1, std::memory_order_relaxed);  // a time jump, bounded
  return tick_clock_us;
}

/// A recording: the first record is already fetched (its time is T_0); records are pushed when
/// their log time is due at the plan's speed, never dropped.
void receive_recording(runtime::InputSource& source, Shared& shared, const Plan& plan) {
  runtime::InputRecord record;
  for (;;) {
    const std::int64_t due =
        plan.mono0_ns +
        static_cast<std::int64_t>(static_cast<double>(source.record_time_us() - plan.t0_us) *
                                  1000.0 / plan.speed);
    if (!sleep_until(due, shared.stop)) return;
    source.copy_record(&record);
    push_input(record, shared, true);
    if (source.next_record(0) != runtime::InputSource::Read::kRecord) break;
    // A log in time order: every record stamped before the next one has been pushed.
    shared.inputs.pushed_through_us.store(source.record_time_us() - 1, std::memory_order_release);
  }
  shared.inputs.ended.store(true, std::memory_order_release);
}

/// Reads a live record, re-stamps it into the tick clock and hands it over (dropped, counted,
/// when the ring is full). Returns what the source's read gave.
runtime::InputSource::Read receive_one(runtime::InputSource& source, Shared& shared,
                                       const Plan& plan, int timeout_ms, ClockPair* now,
                                       runtime::InputRecord* record) {
  const runtime::InputSource::Read got = source.next_record(timeout_ms);
  if (got == runtime::InputSource::Read::kRecord) {
    source.copy_record(record);
    record->time_us = live_time_us(record->time_us, plan, shared, now);
    push_input(*record, shared, false);
  }
  return got;
}

/// A live bus read at every frame's arrival (`daemon.receive_period_ms: 0`).
void receive_live_per_frame(runtime::InputSource& source, Shared& shared, const Plan& plan) {
  runtime::InputRecord record;
  while (!shared.stop.load(std::memory_order_relaxed)) {
    ClockPair now{INT64_MIN, 0};  // read at the frame
    const runtime::InputSource::Read got = receive_one(source, shared, plan, 100, &now, &record);
    if (got == runtime::InputSource::Read::kDown || got == runtime::InputSource::Read::kEnd) {
      // The source waits / re-opens with backoff inside read(); never give up.
      sleep_until(mono_ns() + 10'000'000, shared.stop);
    }
  }
}

/// A live bus drained every receive period, just after each tick time (ReceiveSchedule): the
/// thread wakes once a period instead of at every burst of frames (309 times a second on a
/// 3,000 frames/s bus). A vanished interface is re-opened inside read(), with its backoff.
void receive_live_periodic(runtime::InputSource& source, Shared& shared, const Plan& plan) {
  runtime::InputRecord record;
  const ReceiveSchedule schedule(plan.mono0_ns, plan.period_ns, plan.receive_period_ns);
  std::int64_t next = schedule.first_ns();
  while (sleep_until(next, shared.stop)) {
    ClockPair clocks = read_clocks();
    while (receive_one(source, shared, plan, 0, &clocks, &record) ==
           runtime::InputSource::Read::kRecord) {
    }
    next = schedule.next_ns(next, mono_ns());
  }
}

/// A live bus: frames re-stamped into the tick clock, dropped (counted) when the ring is full.
void receive_live(runtime::InputSource& source, Shared& shared, const Plan& plan) {
  if (plan.receive_period_ns > 0) {
    receive_live_periodic(source, shared, plan);
  } else {
    receive_live_per_frame(source, shared, plan);
  }
}

// --------------------------------------------------------------------------- estimator thread

/// The tick driver's clock at `--speed max`: every tick at once, until a stop is requested.
class StopClock final : public runtime::TickClock {
 public:
  explicit StopClock(const std::atomic<bool>& stop) : stop_(stop) {}
  bool wait_for_tick(std::int64_t /*k*/, TimeUs /*t_k*/) override {
    return !stop_.load(std::memory_order_relaxed);
  }

 private:
  const std::atomic<bool>& stop_;
};

void publish_record(const runtime::TickRecord& record, Shared& shared, bool block) {
  while (!shared.queue.push(record)) {
    if (!block || shared.stop.load(std::memory_order_relaxed)) {
      shared.queue_drops.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  sem_post(&shared.queue_sem);
}

/// The source's input health for the status (allocates nothing; about 4 KB copied).
void publish_health(const runtime::InputSource& source, Shared& shared) {
  runtime::InputHealthRecord health;
  source.health_record(&health);
  shared.health.write(health);
}

/// What the estimator thread keeps from tick to tick besides the pipeline.
struct EstimatorLoop {
  TickStats stats;
  scoring::VerdictTally verdicts;  ///< every block's verdict at every tick, for the status
};

void after_tick(const runtime::TickRecord& record, runtime::TickStep& step,
                const runtime::InputSource& source, Shared& shared, const Plan& plan,
                EstimatorLoop& loop, std::int64_t k) {
  loop.verdicts.add(record.events);
  publish_record(record, shared, plan.recorded);
  shared.latest.write(record);
  shared.heartbeat.store(k + 1, std::memory_order_release);
  if (k % plan.snapshot_every_ticks == 0) {
    shared.snapshot.write(SnapshotSlot{step.snapshot(), record.estimate.time_us, true});
  }
  if (k % static_cast<std::int64_t>(std::max(1.0, plan.tick_rate_hz)) == 0) {
    shared.timing.write(loop.stats.summary());
  }
  if (k % static_cast<std::int64_t>(std::max(1.0, plan.tick_rate_hz / 10.0)) == 0) {
    publish_health(source, shared);  // 10 times a second: the status is read once a second
    shared.verdicts.write(loop.verdicts);
  }
}

/// `--speed max`: log time, through the tick driver vmass-replay runs, so the estimates are
/// identical by construction. Returns the ticks run.
std::int64_t run_log_time(runtime::InputSource& source, runtime::TickStep& step, Shared& shared,
                          const Plan& plan, EstimatorLoop& loop) {
  StopClock clock(shared.stop);
  runtime::TickDriver driver(source, plan.tick_rate_hz);
  const runtime::TickRun run = driver.run(clock, [&](std::int64_t k, TimeUs t) {
    const std::int64_t start = mono_ns();
    loop.stats.on_unpaced_tick();
    apply_commands(step, shared);
    const runtime::TickRecord& record = step.tick(k, t, source);
    loop.stats.on_done(mono_ns() - start, false);
    after_tick(record, step, source, shared, plan, loop, k);
  });
  if (!run.any_record) spdlog::warn("{}: no records", source.describe());
  shared.inputs.ended.store(true, std::memory_order_release);
  return run.ticks;
}

/// A live bus or a paced recording: tick k wakes half a period after T_k on CLOCK_MONOTONIC, so
/// that the records stamped up to T_k have time to arrive (a recording's record stamped T_k is
/// pushed at mono0 + k P; a live frame is read within microseconds of its kernel stamp when the
/// receive thread is not starved). The estimate is P / 2 (5 ms at 100 Hz) later than it could
/// be, which nothing that follows a mass needs.
class MonotonicClock final : public runtime::TickClock {
 public:
  MonotonicClock(const Plan& plan, const std::atomic<bool>& stop, TickStats& stats)
      : plan_(plan),
        stop_(stop),
        stats_(stats),
        max_behind_ticks_(std::max<std::int64_t>(1, kNsPerSecond / plan.period_ns)) {}

  bool wait_for_tick(std::int64_t k, TimeUs /*t_k*/) override {
    const std::int64_t deadline = deadline_ns(k);
    if (stop_.load(std::memory_order_relaxed) || !sleep_until(deadline, stop_)) return false;
    wake_ns_ = mono_ns();
    stats_.on_wake(deadline, wake_ns_);
    return true;
  }
  /// Right after tick k's computation (before it is published): its time and overrun.
  void computed(std::int64_t k) {
    const std::int64_t done = mono_ns();
    stats_.on_done(done - wake_ns_, done > deadline_ns(k + 1));
  }
  /// A live bus after a long stall (suspend, debugger): the missed ticks are given up, counted,
  /// after 1 s. A recording never skips: a replay the machine cannot keep up with runs late
  /// (overruns counted) and still gives the offline estimates.
  std::int64_t next_tick(std::int64_t k) override {
    const std::int64_t behind = (mono_ns() - deadline_ns(k + 1)) / plan_.period_ns;
    if (plan_.recorded || behind <= max_behind_ticks_) return k + 1;
    stats_.on_skipped(behind);
    return k + 1 + behind;
  }

 private:
  std::int64_t deadline_ns(std::int64_t k) const {
    return plan_.mono0_ns + plan_.period_ns / 2 + k * plan_.period_ns;
  }

  const Plan& plan_;
  const std::atomic<bool>& stop_;
  TickStats& stats_;
  std::int64_t max_behind_ticks_;
  std::int64_t wake_ns_ = 0;
};

/// A live bus or a paced recording, from the receive thread's ring: the tick driver applies the
/// records stamped <= T_k (a recording's tick waits for a lagging receive thread, so it sees
/// exactly what offline replay sees; a live frame read more than P / 2 after its stamp is
/// applied at the next tick and counted as late). Returns the ticks passed.
std::int64_t run_paced(runtime::InputSource& source, runtime::TickStep& step, Shared& shared,
                       const Plan& plan, EstimatorLoop& loop) {
  MonotonicClock clock(plan, shared.stop, loop.stats);
  runtime::RingFeed feed(shared.inputs, plan.recorded, shared.stop);
  runtime::TickDriver driver(source, feed, runtime::TickGrid(plan.t0_us, plan.tick_rate_hz));
  const runtime::TickRun run = driver.run(clock, [&](std::int64_t k, TimeUs t) {
    apply_commands(step, shared);
    const runtime::TickRecord& record = step.tick(k, t, source);
    clock.computed(k);
    shared.late_records.store(driver.progress().late_records, std::memory_order_relaxed);
    after_tick(record, step, source, shared, plan, loop, k);
  });
  return run.ticks;
}

}  // namespace

void receive_thread(runtime::InputSource& source, Shared& shared, const Plan& plan) {
  if (!plan.recorded) {
    receive_live(source, shared, plan);
  } else if (plan.has_first_record) {
    receive_recording(source, shared, plan);
  } else {
    shared.inputs.ended.store(true, std::memory_order_release);
  }
}

void estimator_thread(runtime::InputSource& source, runtime::TickStep& step, Shared& shared,
                      const Plan& plan) {
  apply_realtime(plan.realtime);
  EstimatorLoop loop{TickStats(plan.period_ns), {}};
  const std::int64_t ticks = plan.max_speed ? run_log_time(source, step, shared, plan, loop)
                                            : run_paced(source, step, shared, plan, loop);
  // Final state for the main thread (status, persistence).
  shared.timing.write(loop.stats.summary());
  shared.verdicts.write(loop.verdicts);
  publish_health(source, shared);
  shared.snapshot.write(SnapshotSlot{step.snapshot(), step.last().estimate.time_us, ticks > 0});
  shared.estimator_done.store(plan.recorded && shared.inputs.ended.load());
}

// --------------------------------------------------------------------------- status and publisher

void copy_input_health(const runtime::InputSource& source, const runtime::InputHealthRecord& h,
                       DaemonStatus* s) {
  for (int i = 0; i < kInputCount; ++i) {
    const runtime::InputHealthRecord::InputEntry& e = h.inputs[static_cast<std::size_t>(i)];
    InputHealth& out = s->inputs[static_cast<std::size_t>(i)];
    out.stale = e.stale;
    out.invalid = e.invalid;
    out.implausible = e.implausible;
    out.counter_fail = e.counter_fail;
    out.checksum_fail = e.checksum_fail;
    out.reason = signals::describe(e.verdict, source.message_name(e.verdict.message));
  }
  s->messages.clear();
  for (int k = 0; k < h.message_count; ++k) {
    const runtime::InputHealthRecord::MessageEntry& m = h.messages[static_cast<std::size_t>(k)];
    s->messages.push_back(MessageHealth{source.message_name(m.message), m.valid, m.counter_fail,
                                        m.checksum_fail, m.too_fast, m.too_long});
  }
  s->bus_valid = h.bus_valid;
}

DaemonStatus gather_status(const StatusContext& ctx, Shared& shared, bool stopping) {
  DaemonStatus s;
  s.source = ctx.source_name;
  s.tick_rate_hz = ctx.tick_rate_hz;
  s.uptime_s = static_cast<double>(mono_ns() - ctx.start_mono_ns) * 1e-9;
  s.has_tick = shared.heartbeat.load(std::memory_order_acquire) > 0;
  if (s.has_tick) s.last = shared.latest.read();
  copy_counters(ctx.source->counters(), &s);
  s.frames_dropped += shared.input_drops.load(std::memory_order_relaxed);
  s.timing = shared.timing.read();
  s.timing.ticks = shared.heartbeat.load(std::memory_order_acquire);  // fresher than the summary
  s.publish_queue_drops = shared.queue_drops.load(std::memory_order_relaxed);
  s.publish_failures = shared.publish_failures.load(std::memory_order_relaxed);
  const runtime::SourceCounters& c = ctx.source->counters();
  s.frames_reordered = c.reordered.load(std::memory_order_relaxed);
  s.frames_late_dropped = c.late_dropped.load(std::memory_order_relaxed);
  s.time_jumps = c.time_jumps.load(std::memory_order_relaxed) +
                 shared.live_clock_steps.load(std::memory_order_relaxed);
  s.state_saves = shared.state_saves.load(std::memory_order_relaxed);
  s.state_restored = ctx.state_restored;
  copy_input_health(*ctx.source, shared.health.read(), &s);
  s.verdicts = shared.verdicts.read();
  s.commands_received = shared.commands_received.load(std::memory_order_relaxed);
  const CommandResult command = shared.command_result.read();
  s.last_command_utime = command.utime;
  s.last_command_result = command.text;
  const runtime::SourceHealth health = ctx.source->health();
  s.detail = health.detail;
  if (stopping) {
    s.state = DaemonState::kStopping;
  } else if (health.state == runtime::SourceState::kDown) {
    s.state = DaemonState::kInputLost;
  } else if (health.state == runtime::SourceState::kEnded ||
             shared.inputs.ended.load(std::memory_order_relaxed)) {
    s.state = DaemonState::kInputEnded;
  } else {
    s.state = s.has_tick ? DaemonState::kRunning : DaemonState::kStarting;
  }
  return s;
}

void publisher_thread(LcmPublisher& publisher, Shared& shared, const StatusContext& ctx,
                      double status_period_s) {
  const auto period_ns = static_cast<std::int64_t>(status_period_s * 1e9);
  std::int64_t next_status = mono_ns() + period_ns;
  PublishBackoff backoff(publisher.url());
  // One message (a tick's estimate and pairs, or the status), unless backing off.
  auto send = [&](auto&& publish) {
    const std::int64_t now = mono_ns();
    if (backoff.try_now(now)) backoff.record(publish(), now);
    shared.publish_failures.store(backoff.failures(), std::memory_order_relaxed);
    shared.published.store(backoff.published(), std::memory_order_relaxed);
  };
  runtime::TickRecord record;
  auto drain = [&] {
    while (shared.queue.pop(&record)) send([&] { return publisher.on_tick(record); });
  };
  for (;;) {
    const std::int64_t wait_until = std::min(next_status, mono_ns() + kPollNs);
    const timespec ts = to_timespec(wait_until);
    sem_clockwait(&shared.queue_sem, CLOCK_MONOTONIC, &ts);
    drain();
    const std::int64_t now = mono_ns();
    if (now >= next_status) {
      send([&] { return publisher.publish_status(gather_status(ctx, shared, false)); });
      next_status += period_ns;
      if (next_status <= now) next_status = now + period_ns;
    }
    if (shared.stop_publisher.load(std::memory_order_acquire)) {
      drain();
      return;
    }
  }
}

std::string summary_line(const DaemonStatus& s) {
  char buf[256];
  const vmass::Estimate& e = s.last.estimate;
  if (s.has_tick && e.mass_known) {
    std::snprintf(buf, sizeof buf, "%s: %.0f kg [%.0f, %.0f] %s; %s %s; %lld ticks, %lld overruns",
                  std::string(daemon_state_name(s.state)).c_str(), e.mass_kg, e.ci_low_kg,
                  e.ci_high_kg, std::string(vmass::status_name(e.status)).c_str(), s.source.c_str(),
                  s.detail.empty() ? "ok" : s.detail.c_str(),
                  static_cast<long long>(s.timing.ticks),
                  static_cast<long long>(s.timing.overruns));
  } else {
    std::snprintf(buf, sizeof buf, "%s: no mass yet (%s); %s %s; %lld ticks",
                  std::string(daemon_state_name(s.state)).c_str(),
                  s.has_tick ? std::string(vmass::reason_name(e.reason)).c_str() : "no tick",
                  s.source.c_str(), s.detail.empty() ? "ok" : s.detail.c_str(),
                  static_cast<long long>(s.timing.ticks));
  }
  return buf;
}

bool save_snapshot(const std::string& path, const SnapshotSlot& slot, const PipelineParams& params,
                   Shared& shared) {
  if (path.empty() || !slot.valid) return false;
  std::string error;
  switch (save_pipeline_state(path, slot.snapshot, slot.time_us, params, &error)) {
    case StateSave::kSaved:
      shared.state_saves.fetch_add(1, std::memory_order_relaxed);
      return true;
    case StateSave::kNothingToSave:
      return false;
    case StateSave::kNotBelievable:
    case StateSave::kFailed:
      spdlog::warn("state not saved: {}", error);
      return false;
  }
  return false;
}

}  // namespace vmass::service::daemon
