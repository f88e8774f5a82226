#include "daemon.hpp"

#include <pthread.h>
#include <sched.h>
#include <semaphore.h>
#include <signal.h>
#include <sys/mman.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>

#include <spdlog/spdlog.h>
#include <lcm/lcm-cpp.hpp>

#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/candump_frame_source.hpp"
#include "vmass/runtime/samples_csv_source.hpp"
#include "vmass/runtime/seqlock.hpp"
#include "vmass/runtime/socketcan_frame_source.hpp"
#include "vmass/runtime/tick_driver.hpp"
#include "vmass/runtime/tick_grid.hpp"
#include "vmass/runtime/tick_step.hpp"
#include "vmass/service/lcm_publisher.hpp"
#include "vmass/service/spsc_queue.hpp"
#include "vmass/service/state_store.hpp"
#include "vmass/service/systemd_notifier.hpp"
#include "vmass/service/tick_stats.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmassd {
namespace {

using vmass::TimeUs;
namespace svc = vmass::service;
namespace rt = vmass::runtime;

constexpr std::int64_t kNsPerSecond = 1'000'000'000;
constexpr std::int64_t kPollNs = 100'000'000;  // longest uninterrupted wait: 100 ms
// receive -> estimator ring, records (~100 B each): 4096 frames are ~1 s of a busy 500 kbit/s
// bus after the kernel's DBC-id filter, many ticks of slack for the estimator thread.
constexpr std::size_t kInputQueueRecords = 4096;

std::int64_t mono_ns() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * kNsPerSecond + ts.tv_nsec;
}

TimeUs realtime_us() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<TimeUs>(ts.tv_sec) * 1'000'000 + ts.tv_nsec / 1000;
}

timespec to_timespec(std::int64_t ns) {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(ns / kNsPerSecond);
  ts.tv_nsec = static_cast<long>(ns % kNsPerSecond);
  return ts;
}

/// Absolute sleep on CLOCK_MONOTONIC until deadline_ns, in slices of at most 100 ms so that a
/// stop request is seen. Returns false when stopped first.
bool sleep_until(std::int64_t deadline_ns, const std::atomic<bool>& stop) {
  while (!stop.load(std::memory_order_relaxed)) {
    const std::int64_t now = mono_ns();
    if (now >= deadline_ns) return true;
    const std::int64_t until = std::min(deadline_ns, now + kPollNs);
    const timespec ts = to_timespec(until);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
  }
  return false;
}

struct SnapshotSlot {
  vmass::PipelineSnapshot snapshot;
  TimeUs time_us = 0;
  bool valid = false;
};

/// Everything the threads share. Allocated once at start-up.
struct Shared {
  explicit Shared(std::size_t queue_capacity) : inputs(kInputQueueRecords), queue(queue_capacity) {
    sem_init(&queue_sem, 0, 0);
  }
  ~Shared() { sem_destroy(&queue_sem); }

  std::atomic<bool> stop{false};             ///< main -> receive, estimator
  std::atomic<bool> stop_publisher{false};   ///< main -> publisher (after the estimator joined)
  std::atomic<bool> estimator_done{false};   ///< a recording was played to its end
  svc::SpscQueue<rt::InputRecord> inputs;    ///< receive -> estimator (frames, rows)
  std::atomic<std::int64_t> input_drops{0};  ///< live records the full input ring refused
  svc::SpscQueue<rt::TickRecord> queue;      ///< estimator -> publisher
  sem_t queue_sem;
  std::atomic<std::int64_t> queue_drops{0};
  rt::SeqLock<rt::TickRecord> latest;          ///< estimator -> main, publisher (status)
  rt::SeqLock<svc::TickTimingSummary> timing;  ///< estimator -> status
  rt::SeqLock<SnapshotSlot> snapshot;          ///< estimator -> main (persistence)
  std::atomic<std::int64_t> heartbeat{0};      ///< ticks run (watchdog evidence)
  std::atomic<std::int64_t> state_saves{0};
  std::atomic<bool> input_ended{false};
  std::atomic<std::int64_t> late_records{0};  ///< applied after the tick they belonged to
  /// A recording: every record stamped <= this is in the input ring (receive -> estimator).
  std::atomic<TimeUs> pushed_through_us{INT64_MIN};
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
  svc::RealtimeSettings realtime;

  /// T_k in the input clock: the grid every front end ticks on (runtime::TickGrid).
  TimeUs tick_time(std::int64_t k) const { return rt::TickGrid(t0_us, tick_rate_hz).time_of(k); }
};

void apply_realtime(const svc::RealtimeSettings& rt) {
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
void push_input(const rt::InputRecord& record, Shared& shared, bool block) {
  while (!shared.inputs.push(record)) {
    if (!block) {
      shared.input_drops.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    if (shared.stop.load(std::memory_order_relaxed)) return;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
}

/// CLOCK_REALTIME and CLOCK_MONOTONIC read together: the pair of the tightest of up to three
/// realtime-monotonic-realtime brackets (a preemption between two reads would skew it).
struct ClockPair {
  TimeUs realtime_us = 0;
  std::int64_t mono_ns = 0;
};
ClockPair read_clocks() {
  ClockPair best;
  TimeUs best_width = INT64_MAX;
  for (int i = 0; i < 3 && best_width > 20; ++i) {
    const TimeUs rt1 = realtime_us();
    const std::int64_t mono = mono_ns();
    const TimeUs rt2 = realtime_us();
    if (rt2 - rt1 < best_width) {
      best_width = rt2 - rt1;
      best = ClockPair{rt1 + (rt2 - rt1) / 2, mono};
    }
  }
  return best;
}

/// A live frame's time in the tick clock: its kernel stamp (CLOCK_REALTIME) moved by the tick
/// clock's offset from CLOCK_REALTIME now. A stamp older than 1 s or in the future means the
/// wall clock was stepped (or the frame has no stamp): then the time it was read. So the
/// inputs' ages and timeouts never depend on CLOCK_REALTIME steps, which are common on a
/// vehicle PC that sets its clock after boot (GNSS, NTP).
TimeUs live_time_us(TimeUs kernel_stamp_us, const Plan& plan) {
  const ClockPair now = read_clocks();
  const TimeUs tick_clock_us = plan.t0_us + (now.mono_ns - plan.mono0_ns) / 1000;
  const TimeUs waited = now.realtime_us - kernel_stamp_us;
  return (waited >= 0 && waited <= 1'000'000) ? tick_clock_us - waited : tick_clock_us;
}

void receive_thread(rt::InputSource& source, Shared& shared, const Plan& plan) {
  rt::InputRecord record;
  if (plan.recorded) {
    if (!plan.has_first_record) {
      shared.input_ended.store(true, std::memory_order_release);
      return;
    }
    // The first record is already fetched (its time is T_0). Pace records by log time.
    for (;;) {
      const std::int64_t due =
          plan.mono0_ns +
          static_cast<std::int64_t>(static_cast<double>(source.record_time_us() - plan.t0_us) *
                                    1000.0 / plan.speed);
      if (!sleep_until(due, shared.stop)) return;
      source.fetch(&record);
      push_input(record, shared, true);
      if (source.read(0) != rt::InputSource::Read::kRecord) break;
      // A log in time order: every record stamped before the next one has been pushed.
      shared.pushed_through_us.store(source.record_time_us() - 1, std::memory_order_release);
    }
    shared.input_ended.store(true, std::memory_order_release);
    return;
  }
  while (!shared.stop.load(std::memory_order_relaxed)) {
    switch (source.read(100)) {
      case rt::InputSource::Read::kRecord:
        source.fetch(&record);
        record.time_us = live_time_us(record.time_us, plan);
        push_input(record, shared, false);
        break;
      case rt::InputSource::Read::kTimeout:
        break;
      case rt::InputSource::Read::kDown:
      case rt::InputSource::Read::kEnd:
        // The source waits / re-opens with backoff inside read(); never give up.
        sleep_until(mono_ns() + 10'000'000, shared.stop);
        break;
    }
  }
}

// --------------------------------------------------------------------------- estimator thread

/// The tick driver's clock at `--speed max`: every tick at once, until a stop is requested.
class StopClock final : public rt::TickClock {
 public:
  explicit StopClock(const std::atomic<bool>& stop) : stop_(stop) {}
  bool wait_for_tick(std::int64_t /*k*/, TimeUs /*t_k*/) override {
    return !stop_.load(std::memory_order_relaxed);
  }

 private:
  const std::atomic<bool>& stop_;
};

void publish_record(const rt::TickRecord& record, Shared& shared, bool block) {
  while (!shared.queue.push(record)) {
    if (!block || shared.stop.load(std::memory_order_relaxed)) {
      shared.queue_drops.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  sem_post(&shared.queue_sem);
}

void after_tick(const rt::TickRecord& record, rt::TickStep& loop, Shared& shared, const Plan& plan,
                svc::TickStats& stats, std::int64_t k) {
  publish_record(record, shared, plan.recorded);
  shared.latest.write(record);
  shared.heartbeat.store(k + 1, std::memory_order_release);
  if (k % plan.snapshot_every_ticks == 0) {
    shared.snapshot.write(SnapshotSlot{loop.pipeline().snapshot(), record.estimate.time_us, true});
  }
  if (k % static_cast<std::int64_t>(std::max(1.0, plan.tick_rate_hz)) == 0) {
    shared.timing.write(stats.summary());
  }
}

// NOLINTNEXTLINE(readability-function-size): not split yet (issue 9)
void estimator_thread(rt::InputSource& source, rt::TickStep& loop, Shared& shared,
                      const Plan& plan) {
  apply_realtime(plan.realtime);
  svc::TickStats stats(plan.period_ns);
  std::int64_t k = 0;

  if (plan.max_speed) {
    // Log time, through the tick driver vmass-replay runs: identical estimates by construction.
    StopClock clock(shared.stop);
    rt::TickDriver driver(source, plan.tick_rate_hz);
    const rt::TickRun run = driver.run(clock, [&](std::int64_t tick, TimeUs t) {
      const std::int64_t start = mono_ns();
      stats.on_unpaced_tick();
      const rt::TickRecord& tick_record = loop.tick(tick, t, source);
      stats.on_done(mono_ns() - start, false);
      after_tick(tick_record, loop, shared, plan, stats, tick);
    });
    if (!run.any_record) spdlog::warn("{}: no records", source.describe());
    k = run.ticks;
    shared.input_ended.store(true, std::memory_order_release);
  } else {
    const std::int64_t max_behind_ticks =
        std::max<std::int64_t>(1, static_cast<std::int64_t>(kNsPerSecond / plan.period_ns));
    rt::InputRecord held;  // popped from the ring, not applied yet (stamped after its tick)
    bool has_held = false;
    TimeUs last_record_us = 0;
    bool has_record = false;
    // Tick k wakes half a period after T_k, so that the records stamped up to T_k have time to
    // arrive (a recording's record stamped T_k is pushed at mono0 + k P; a live frame is read
    // within microseconds of its kernel stamp when the receive thread is not starved). A
    // recording's tick also waits for a lagging receive thread, so it sees exactly what offline
    // replay sees; a live frame read more than P / 2 after its stamp is applied at the next tick
    // and counted as late. The estimate is P / 2 (5 ms at 100 Hz) later than it could be, which
    // nothing that follows a mass needs.
    const std::int64_t offset_ns = plan.period_ns / 2;
    TimeUs previous_t = INT64_MIN;
    while (!shared.stop.load(std::memory_order_relaxed)) {
      const std::int64_t deadline = plan.mono0_ns + offset_ns + k * plan.period_ns;
      if (!sleep_until(deadline, shared.stop)) break;
      const std::int64_t wake = mono_ns();
      stats.on_wake(deadline, wake);
      const TimeUs t = plan.tick_time(k);
      // Fold the records received since the last tick into the table; records stamped after
      // this tick wait for their own (as in offline replay: tick k sees exactly the records
      // stamped <= T_k). Live records are stamped in the tick clock, so a record is held for
      // one tick at most.
      auto drain = [&] {
        for (;;) {
          if (!has_held) {
            if (!shared.inputs.pop(&held)) return;
            has_held = true;
          }
          if (held.time_us > t) return;
          if (held.time_us <= previous_t) {
            shared.late_records.fetch_add(1, std::memory_order_relaxed);
          }
          source.apply(held);
          has_held = false;
          if (!has_record || held.time_us > last_record_us) last_record_us = held.time_us;
          has_record = true;
        }
      };
      drain();
      if (plan.recorded) {
        // A recording: wait until the receive thread has pushed every record stamped <= T_k
        // (it is due P / 2 earlier; this waits only when it lags), so that tick k sees exactly
        // what offline replay sees at any speed; drain meanwhile, so that a full ring cannot
        // block the receive thread. A held record (stamped after T_k) means they all came.
        // The wait counts in the tick's compute time.
        while (!has_held && shared.pushed_through_us.load(std::memory_order_acquire) < t &&
               !shared.input_ended.load(std::memory_order_acquire) &&
               !shared.stop.load(std::memory_order_relaxed)) {
          std::this_thread::sleep_for(std::chrono::microseconds(50));
          drain();
        }
      }
      // Read before the last drain: once it is set, every record is in the ring.
      const bool ended = plan.recorded && shared.input_ended.load(std::memory_order_acquire);
      drain();
      // A finished recording: tick up to its last record, as offline replay does.
      if (ended && !has_held && (!has_record || t > last_record_us)) break;
      const rt::TickRecord& record = loop.tick(k, t, source);
      previous_t = t;
      const std::int64_t done = mono_ns();
      ++k;
      const std::int64_t next_deadline = plan.mono0_ns + offset_ns + k * plan.period_ns;
      stats.on_done(done - wake, done > next_deadline);
      after_tick(record, loop, shared, plan, stats, k - 1);
      // A live bus after a long stall (suspend, debugger): give the missed ticks up, counted,
      // after 1 s. A recording never skips: a replay the machine cannot keep up with runs late
      // (overruns counted) and still gives the offline estimates.
      const std::int64_t behind = (mono_ns() - next_deadline) / plan.period_ns;
      if (!plan.recorded && behind > max_behind_ticks) {
        k += behind;
        stats.on_skipped(behind);
      }
    }
  }
  // Final state for the main thread (status, persistence).
  shared.timing.write(stats.summary());
  shared.snapshot.write(
      SnapshotSlot{loop.pipeline().snapshot(), loop.last().estimate.time_us, k > 0});
  shared.estimator_done.store(plan.recorded && shared.input_ended.load());
}

// --------------------------------------------------------------------------- status and publisher

struct StatusContext {
  const rt::InputSource* source = nullptr;
  std::string source_name;
  double tick_rate_hz = 100.0;
  std::int64_t start_mono_ns = 0;
  bool state_restored = false;
};

svc::DaemonStatus gather_status(const StatusContext& ctx, Shared& shared, bool stopping) {
  svc::DaemonStatus s;
  s.source = ctx.source_name;
  s.tick_rate_hz = ctx.tick_rate_hz;
  s.uptime_s = static_cast<double>(mono_ns() - ctx.start_mono_ns) * 1e-9;
  s.has_tick = shared.heartbeat.load(std::memory_order_acquire) > 0;
  if (s.has_tick) s.last = shared.latest.read();
  svc::copy_counters(ctx.source->counters(), &s);
  s.frames_dropped += shared.input_drops.load(std::memory_order_relaxed);
  s.timing = shared.timing.read();
  s.timing.ticks = shared.heartbeat.load(std::memory_order_acquire);  // fresher than the summary
  s.publish_queue_drops = shared.queue_drops.load(std::memory_order_relaxed);
  s.state_saves = shared.state_saves.load(std::memory_order_relaxed);
  s.state_restored = ctx.state_restored;
  const rt::SourceHealth health = ctx.source->health();
  s.detail = health.detail;
  if (stopping) {
    s.state = svc::DaemonState::kStopping;
  } else if (health.state == rt::SourceState::kDown) {
    s.state = svc::DaemonState::kInputLost;
  } else if (health.state == rt::SourceState::kEnded ||
             shared.input_ended.load(std::memory_order_relaxed)) {
    s.state = svc::DaemonState::kInputEnded;
  } else {
    s.state = s.has_tick ? svc::DaemonState::kRunning : svc::DaemonState::kStarting;
  }
  return s;
}

void publisher_thread(svc::LcmPublisher& publisher, Shared& shared, const StatusContext& ctx,
                      double status_period_s) {
  const auto period_ns = static_cast<std::int64_t>(status_period_s * 1e9);
  std::int64_t next_status = mono_ns() + period_ns;
  rt::TickRecord record;
  for (;;) {
    const std::int64_t wait_until = std::min(next_status, mono_ns() + kPollNs);
    const timespec ts = to_timespec(wait_until);
    sem_clockwait(&shared.queue_sem, CLOCK_MONOTONIC, &ts);
    while (shared.queue.pop(&record)) publisher.on_tick(record);
    const std::int64_t now = mono_ns();
    if (now >= next_status) {
      publisher.publish_status(gather_status(ctx, shared, false));
      next_status += period_ns;
      if (next_status <= now) next_status = now + period_ns;
    }
    if (shared.stop_publisher.load(std::memory_order_acquire)) {
      while (shared.queue.pop(&record)) publisher.on_tick(record);
      return;
    }
  }
}

std::string summary_line(const svc::DaemonStatus& s) {
  char buf[256];
  const vmass::Estimate& e = s.last.estimate;
  if (s.has_tick && e.mass_known) {
    std::snprintf(buf, sizeof buf, "%s: %.0f kg [%.0f, %.0f] %s; %s %s; %lld ticks, %lld overruns",
                  std::string(svc::daemon_state_name(s.state)).c_str(), e.mass_kg, e.ci_low_kg,
                  e.ci_high_kg, std::string(vmass::status_name(e.status)).c_str(), s.source.c_str(),
                  s.detail.empty() ? "ok" : s.detail.c_str(),
                  static_cast<long long>(s.timing.ticks),
                  static_cast<long long>(s.timing.overruns));
  } else {
    std::snprintf(buf, sizeof buf, "%s: no mass yet (%s); %s %s; %lld ticks",
                  std::string(svc::daemon_state_name(s.state)).c_str(),
                  s.has_tick ? std::string(vmass::reason_name(e.reason)).c_str() : "no tick",
                  s.source.c_str(), s.detail.empty() ? "ok" : s.detail.c_str(),
                  static_cast<long long>(s.timing.ticks));
  }
  return buf;
}

bool save_snapshot(const std::string& path, const SnapshotSlot& slot, std::uint64_t fingerprint,
                   Shared& shared) {
  if (path.empty() || !slot.valid || !slot.snapshot.has_prior) return false;
  svc::SavedState state;
  state.snapshot = slot.snapshot;
  state.saved_time_us = slot.time_us;
  state.fingerprint = fingerprint;
  std::string error;
  if (!svc::save_state_file(path, state, &error)) {
    spdlog::warn("state not saved: {}", error);
    return false;
  }
  shared.state_saves.fetch_add(1, std::memory_order_relaxed);
  return true;
}

}  // namespace

// NOLINTNEXTLINE(readability-function-size): not split yet (issue 9)
int run(const Options& options) {
  const std::int64_t start_mono = mono_ns();
  // Signals: taken by the main thread with sigtimedwait. Blocked first, so that every thread
  // started later (ours, and any a library starts) inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGTERM);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGHUP);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  ::signal(SIGPIPE, SIG_IGN);
  // ------------------------------------------------------------------ configuration
  vmass::ConfigLoad loaded = vmass::load_config(options.config_path);
  if (!loaded.ok()) {
    spdlog::error("{}", loaded.error);
    return 2;
  }
  const vmass::Config& config = *loaded.config;
  svc::ServiceSettingsLoad settings_load = svc::load_service_settings(config);
  if (!settings_load.ok()) {
    spdlog::error("{}", settings_load.error);
    return 2;
  }
  svc::ServiceSettings settings = settings_load.settings;
  if (!options.lcm_url.empty()) settings.lcm.url = options.lcm_url;
  const vmass::PipelineParams& params = config.pipeline;

  Plan plan;
  plan.tick_rate_hz = params.estimator.differencing.tick_rate_hz;
  plan.realtime = settings.daemon.realtime;
  const bool recorded = !options.replay_log.empty() || !options.samples_csv.empty();
  if (!recorded && options.speed != "1") {
    spdlog::error("--speed applies to --replay and --samples only");
    return 2;
  }
  if (options.speed == "max") {
    plan.max_speed = true;
  } else {
    char* end = nullptr;
    plan.speed = std::strtod(options.speed.c_str(), &end);
    if (end == options.speed.c_str() || *end != '\0' || !(plan.speed > 0.0) ||
        !(plan.speed <= 1000.0)) {
      spdlog::error("--speed: expected a factor in (0, 1000] or 'max', got '{}'", options.speed);
      return 2;
    }
  }
  plan.recorded = recorded;
  plan.period_ns = static_cast<std::int64_t>(
      std::llround(1e9 / (plan.tick_rate_hz * (plan.max_speed ? 1.0 : plan.speed))));
  const double persist_ticks = settings.daemon.persist_interval_s * plan.tick_rate_hz / 10.0;
  plan.snapshot_every_ticks = static_cast<int>(std::clamp(persist_ticks, 1.0, 100.0));

  if (settings.daemon.realtime.lock_memory && mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    spdlog::warn(
        "daemon.realtime.lock_memory: mlockall failed ({}); memory may be paged "
        "(grant LimitMEMLOCK=infinity)",
        std::strerror(errno));
  }

  // ------------------------------------------------------------------ input
  std::unique_ptr<rt::InputSource> source;
  std::string error;
  if (!options.samples_csv.empty()) {
    const double timeout_s = settings.daemon.input_timeout_s > 0.0
                                 ? settings.daemon.input_timeout_s
                                 : 5.0 / plan.tick_rate_hz;  // as vmass-replay
    source = rt::SamplesCsvSource::open(options.samples_csv, timeout_s, &error);
    if (!source) {
      spdlog::error("{}", error);
      return 1;
    }
  } else {
    // can.dbc and can.inputs: the compiled DBC and the signal mapping of the SignalTable.
    vmass::signals::CanInputsLoad can = vmass::signals::load_can_inputs(config);
    if (!can.ok()) {
      spdlog::error("{}", can.error);
      return 2;
    }
    const vmass::signals::CanInputs& can_inputs = *can.inputs;
    if (!can_inputs.warnings.empty()) {
      spdlog::info("{}: {} format deviations tolerated (vmass-can check lists them)",
                   can_inputs.dbc_path, can_inputs.warnings.size());
    }
    std::string unmapped;
    for (int i = 0; i < vmass::kInputCount; ++i) {
      const auto input = static_cast<vmass::Input>(i);
      if (can_inputs.mapping.find(input) == nullptr) {
        unmapped += (unmapped.empty() ? "" : ", ") + std::string(vmass::input_name(input));
      }
    }
    std::string mapped = can_inputs.mapping.describe();
    while (!mapped.empty() && mapped.back() == '\n') mapped.pop_back();
    if (!mapped.empty()) spdlog::info("can.inputs:\n{}", mapped);
    if (!unmapped.empty()) {
      spdlog::warn("can.inputs: not mapped, stay invalid: {}", unmapped);
    }
    std::unique_ptr<rt::FrameSource> frames;
    if (!options.replay_log.empty()) {
      frames = rt::CandumpFrameSource::open(options.replay_log, &error);
    } else {
      vmass::can::SocketCanOptions can_options;
      can_options.interface =
          options.can_interface.empty() ? settings.daemon.can_interface : options.can_interface;
      can_options.filters = vmass::can::filters_for(can_inputs.decoder->database());
      const std::string invalid = can_options.validate();
      if (!invalid.empty()) {
        spdlog::error("{}", invalid);
        return 2;
      }
      frames = rt::SocketCanFrameSource::open(can_options, &error);
    }
    if (!frames) {
      spdlog::error("{}", error);
      return 1;
    }
    source = std::make_unique<rt::CanInputSource>(std::move(frames), can_inputs.decoder,
                                                  can_inputs.mapping);
  }

  // ------------------------------------------------------------------ LCM and state
  lcm::LCM lcm(settings.lcm.url);
  if (!lcm.good()) {
    spdlog::error("cannot open LCM at '{}'", settings.lcm.url);
    return 1;
  }
  rt::TickStep loop(params);

  std::string state_path =
      options.state_file.empty() ? settings.daemon.state_file : options.state_file;
  if (state_path.empty()) {
    const char* dir = std::getenv("STATE_DIRECTORY");  // systemd StateDirectory=
    if (dir != nullptr && dir[0] != '\0') {
      std::string first(dir);
      first = first.substr(0, first.find(':'));
      state_path = first + "/vmassd.state";
    }
  }
  const std::uint64_t fingerprint = svc::state_fingerprint(params);
  bool restored = false;
  if (!state_path.empty() && !options.no_restore) {
    const svc::StateLoad state = svc::load_state_file(state_path, fingerprint);
    if (state.status == svc::StateLoadStatus::kLoaded) {
      restored = loop.pipeline().restore(state.state.snapshot);
      if (restored) {
        spdlog::info(
            "restored {} estimate {:.1f} kg from {} ({} pairs); a standstill will "
            "re-check the load",
            vmass::regressor_type_name(params.estimator.type), loop.pipeline().estimate().mass_kg,
            state_path, state.state.snapshot.pairs_used);
      } else {
        spdlog::warn("{}: saved state refused by the estimator; starting fresh", state_path);
      }
    } else if (state.status == svc::StateLoadStatus::kRejected) {
      spdlog::warn("{}; starting fresh", state.error);
    }
  }

  // ------------------------------------------------------------------ start
  if (plan.recorded && !plan.max_speed) {  // at max speed the tick driver reads it
    plan.has_first_record = source->read(0) == rt::InputSource::Read::kRecord;
    plan.t0_us = plan.has_first_record ? source->record_time_us() : 0;
    if (!plan.has_first_record) spdlog::warn("{}: no records", source->describe());
  }  // live: T_0 is set with tick 0's CLOCK_MONOTONIC below

  Shared shared(static_cast<std::size_t>(settings.daemon.publish_queue));
  StatusContext ctx;
  ctx.source = source.get();
  ctx.source_name = source->describe();
  ctx.tick_rate_hz = plan.tick_rate_hz;
  ctx.start_mono_ns = start_mono;
  ctx.state_restored = restored;
  svc::LcmPublisher publisher(lcm, settings.lcm, std::string(loop.pipeline().regressor().name()));

  plan.mono0_ns = mono_ns() + 1'000'000;  // first tick 1 ms from now
  if (!plan.recorded) {
    // Live: T_0 is CLOCK_REALTIME at tick 0, so the tick clock reads as the wall clock did at
    // start (and live frames' times are their kernel stamps, give or take a few microseconds).
    const ClockPair now = read_clocks();
    plan.t0_us = now.realtime_us + (plan.mono0_ns - now.mono_ns) / 1000;
  }
  std::thread publisher_worker(publisher_thread, std::ref(publisher), std::ref(shared),
                               std::cref(ctx), settings.lcm.status_period_s);
  std::thread estimator_worker(estimator_thread, std::ref(*source), std::ref(loop),
                               std::ref(shared), std::cref(plan));
  std::thread receive_worker;
  if (!plan.max_speed) {
    receive_worker =
        std::thread(receive_thread, std::ref(*source), std::ref(shared), std::cref(plan));
  }

  svc::SystemdNotifier notifier;
  notifier.notify("READY=1\nSTATUS=" + summary_line(gather_status(ctx, shared, false)));
  spdlog::info("vmassd running: input {}, {} estimator at {} Hz{}, LCM {}{}", ctx.source_name,
               loop.pipeline().regressor().name(), plan.tick_rate_hz,
               plan.recorded ? (plan.max_speed ? std::string(", speed max (log time)")
                                               : ", speed " + options.speed)
                             : std::string(),
               settings.lcm.url,
               state_path.empty() ? std::string(", no state file") : ", state " + state_path);
  if (notifier.watchdog_usec() > 0) {
    spdlog::info("systemd watchdog {} ms: pinging every {} ms while the estimator ticks",
                 notifier.watchdog_usec() / 1000, notifier.watchdog_ping_interval_usec() / 1000);
  }

  // ------------------------------------------------------------------ main loop
  const auto persist_ns = static_cast<std::int64_t>(settings.daemon.persist_interval_s * 1e9);
  std::int64_t next_persist = mono_ns() + persist_ns;
  std::int64_t next_status = mono_ns() + kNsPerSecond;
  std::int64_t heartbeat_at_ping = -1;
  const timespec poll = to_timespec(kPollNs);
  int stop_signal = 0;
  for (;;) {
    siginfo_t info{};
    const int sig = sigtimedwait(&signals, &info, &poll);
    if (sig == SIGTERM || sig == SIGINT) {
      stop_signal = sig;
      break;
    }
    if (sig == SIGHUP) spdlog::info("SIGHUP ignored: restart the service to reload the config");
    if (shared.estimator_done.load(std::memory_order_acquire)) break;
    const std::int64_t now = mono_ns();
    const std::int64_t heartbeat = shared.heartbeat.load(std::memory_order_acquire);
    if (heartbeat != heartbeat_at_ping &&
        notifier.watchdog_due(static_cast<std::uint64_t>(now / 1000))) {
      notifier.watchdog();
      notifier.watchdog_sent(static_cast<std::uint64_t>(now / 1000));
      heartbeat_at_ping = heartbeat;
    }
    if (now >= next_status) {
      notifier.status(summary_line(gather_status(ctx, shared, false)));
      next_status = now + kNsPerSecond;
    }
    if (now >= next_persist) {
      save_snapshot(state_path, shared.snapshot.read(), fingerprint, shared);
      next_persist = now + persist_ns;
    }
  }

  // ------------------------------------------------------------------ orderly stop
  if (stop_signal != 0) spdlog::info("{}: stopping", strsignal(stop_signal));
  notifier.notify("STOPPING=1\nSTATUS=stopping");
  shared.stop.store(true);
  if (receive_worker.joinable()) receive_worker.join();
  estimator_worker.join();
  shared.stop_publisher.store(true, std::memory_order_release);
  sem_post(&shared.queue_sem);
  publisher_worker.join();
  // The estimator thread has stopped: its input table can be read here.
  const std::string input_problems = source->input_report();
  if (!input_problems.empty()) spdlog::info("inputs: {}", input_problems);
  // So is its pipeline: the open Bayes batch enters the saved state instead of being lost.
  SnapshotSlot final_slot = shared.snapshot.read();
  const long pairs_before_flush = loop.pipeline().estimate().pairs_used;
  if (final_slot.valid && loop.pipeline().flush()) {
    final_slot.snapshot = loop.pipeline().snapshot();
    spdlog::info("open batch flushed into the final state: pairs used {} -> {}", pairs_before_flush,
                 loop.pipeline().estimate().pairs_used);
  }
  const bool saved = save_snapshot(state_path, final_slot, fingerprint, shared);
  const svc::DaemonStatus final_status = gather_status(ctx, shared, true);
  publisher.publish_status(final_status);
  spdlog::info(
      "stopped: {}{}; {} estimates published, {} queue drops, {} input records late, jitter "
      "p50/p99/max {:.0f}/{:.0f}/{:.0f} us",
      summary_line(final_status), saved ? ", state saved" : "", publisher.estimates_published(),
      final_status.publish_queue_drops, shared.late_records.load(),
      final_status.timing.jitter_p50_us, final_status.timing.jitter_p99_us,
      final_status.timing.jitter_max_us);
  return 0;
}

}  // namespace vmassd
