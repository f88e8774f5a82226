#include "vmass/service/daemon.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/mman.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <thread>

#include <spdlog/spdlog.h>
#include <lcm/lcm-cpp.hpp>

#include "daemon_clock.hpp"
#include "daemon_threads.hpp"
#include "vmass/config/config.hpp"
#include "vmass/io/excerpt.hpp"
#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/log_frame_source.hpp"
#include "vmass/runtime/recording.hpp"
#include "vmass/runtime/samples_csv_source.hpp"
#include "vmass/runtime/socketcan_frame_source.hpp"
#include "vmass/runtime/tick_step.hpp"
#include "vmass/service/lcm_url.hpp"
#include "vmass/service/pipeline_state.hpp"
#include "vmass/service/receive_schedule.hpp"
#include "vmass/service/state_store.hpp"
#include "vmass/service/stop_signals.hpp"
#include "vmass/service/systemd_notifier.hpp"
#include "vmass/signals/signal_mapping.hpp"
#include "vmass/version.hpp"

namespace vmass::service {
namespace {

using daemon::mono_ns;
using daemon::Plan;
using daemon::Shared;
using daemon::StatusContext;

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitUsage = 2;
constexpr double kMinSpeed = 0.001;  ///< --speed bounds
constexpr double kMaxSpeed = 1000.0;

/// The run's fixed parameters from the options and the config. nullopt (logged) on an error.
std::optional<Plan> make_plan(const DaemonOptions& options, const ServiceSettings& settings,
                              const PipelineParams& params) {
  Plan plan;
  plan.tick_rate_hz = params.estimator.differencing.tick_rate_hz;
  plan.realtime = settings.daemon.realtime;
  plan.recorded = !options.replay_log.empty() || !options.samples_csv.empty();
  if (!plan.recorded && options.speed != "1") {
    spdlog::error("--speed applies to --replay and --samples only");
    return std::nullopt;
  }
  if (options.speed == "max") {
    plan.max_speed = true;
  } else {
    char* end = nullptr;
    plan.speed = std::strtod(options.speed.c_str(), &end);
    // Bounded below too: at 1e-300 a tick would come once in 1e290 years.
    if (end == options.speed.c_str() || *end != '\0' || !(plan.speed >= kMinSpeed) ||
        !(plan.speed <= kMaxSpeed)) {
      spdlog::error("--speed: expected a factor in [0.001, 1000] or 'max', got '{}'",
                    io::excerpt(options.speed));
      return std::nullopt;
    }
  }
  plan.period_ns = static_cast<std::int64_t>(
      std::llround(1e9 / (plan.tick_rate_hz * (plan.max_speed ? 1.0 : plan.speed))));
  plan.receive_period_ns =
      ReceiveSchedule::drain_period_ns(settings.daemon.receive_period_ms, plan.period_ns);
  const double persist_ticks = settings.daemon.persist_interval_s * plan.tick_rate_hz / 10.0;
  plan.snapshot_every_ticks = static_cast<int>(std::clamp(persist_ticks, 1.0, 100.0));
  return plan;
}

void lock_memory(const ServiceSettings& settings) {
  if (settings.daemon.realtime.lock_memory && mlockall(MCL_CURRENT | MCL_FUTURE) != 0) {
    spdlog::warn(
        "daemon.realtime.lock_memory: mlockall failed ({}); memory may be paged "
        "(grant LimitMEMLOCK=infinity)",
        std::strerror(errno));
  }
}

/// Logs what the can.inputs mapping maps, and what it leaves invalid.
void log_mapping(const signals::CanInputs& can) {
  if (!can.warnings.empty()) {
    spdlog::info("{}: {} format deviations tolerated (vmass-can check lists them)", can.dbc_path,
                 can.warnings.size());
  }
  std::string unmapped;
  for (int i = 0; i < kInputCount; ++i) {
    const auto input = static_cast<Input>(i);
    if (can.mapping.find(input) == nullptr) {
      unmapped += (unmapped.empty() ? "" : ", ") + std::string(input_name(input));
    }
  }
  // One message per input: a journal entry each (SignalMapping::describe() gives one per line).
  const std::string mapped = can.mapping.describe();
  for (std::size_t p = 0; p < mapped.size();) {
    const std::size_t eol = std::min(mapped.find('\n', p), mapped.size());
    if (eol > p) spdlog::info("can.inputs.{}", std::string_view(mapped).substr(p, eol - p));
    p = eol + 1;
  }
  if (!unmapped.empty()) spdlog::warn("can.inputs: not mapped, stay invalid: {}", unmapped);
}

struct OpenedInput {
  std::unique_ptr<runtime::InputSource> source;
  int exit_code = kExitOk;                       ///< when source is null
  const runtime::LogFrameSource* log = nullptr;  ///< --replay: the source's frames
};

/// --can IFACE: the interface's frames (its DBC ids only: kernel filters); --can-fd FD: the
/// records of an inherited descriptor, every id (no filters: it need not be a CAN socket), never
/// re-opened. Null (and *exit_code) when it cannot be opened.
std::unique_ptr<runtime::FrameSource> open_socketcan(const DaemonOptions& options,
                                                     const ServiceSettings& settings,
                                                     const can::Database& db, int* exit_code) {
  if (options.can_fd >= 0) {
    if (::fcntl(options.can_fd, F_GETFD) < 0) {
      spdlog::error("--can-fd {}: not an open descriptor", options.can_fd);
      *exit_code = kExitUsage;
      return nullptr;
    }
    auto reader =
        std::make_unique<can::SocketCanReader>(options.can_fd, can::SocketCanReader::Opener{});
    return std::make_unique<runtime::SocketCanFrameSource>(std::move(reader),
                                                           "fd" + std::to_string(options.can_fd));
  }
  can::SocketCanOptions can_options;
  can_options.interface =
      options.can_interface.empty() ? settings.daemon.can_interface : options.can_interface;
  can_options.filters = can::filters_for(db);
  if (const std::string invalid = can_options.validate(); !invalid.empty()) {
    spdlog::error("{}", invalid);
    *exit_code = kExitUsage;
    return nullptr;
  }
  std::string error;
  std::unique_ptr<runtime::FrameSource> frames =
      runtime::SocketCanFrameSource::open(can_options, &error);
  if (!frames) {
    spdlog::error("{}", error);
    *exit_code = kExitFailure;
  }
  return frames;
}

/// --replay LOG: a log of any format through the config's can: mapping, opened as vmass-replay
/// opens it (runtime::open_log_recording).
OpenedInput open_replay(const DaemonOptions& options, const Config& config) {
  runtime::LogRecording recording = runtime::open_log_recording(options.replay_log, config);
  if (!recording.source) {
    spdlog::error("{}", recording.error);
    return {nullptr, kExitUsage};
  }
  log_mapping(*recording.can);
  runtime::LogFrameSource* log = recording.log;
  spdlog::info("{}: {}", options.replay_log, can::log_format_name(log->format()));
  if (!options.replay_interface.empty()) {
    log->select_interface(options.replay_interface);
    spdlog::info("{}: interface {} only", options.replay_log, options.replay_interface);
  }
  log->on_error([log](const can::CandumpError& e) {
    if (log->stats().corrupt <= 10) spdlog::warn("{} (skipped)", e.message);
  });
  return {std::move(recording.source), kExitOk, log};
}

/// --can IFACE or --can-fd FD: the bus's frames through the config's can: mapping.
OpenedInput open_live(const DaemonOptions& options, const Config& config,
                      const ServiceSettings& settings) {
  signals::CanInputsLoad can = signals::load_can_inputs(config);
  if (!can.ok()) {
    spdlog::error("{}", can.error);
    return {nullptr, kExitUsage};
  }
  log_mapping(*can.inputs);
  int exit_code = kExitOk;
  std::unique_ptr<runtime::FrameSource> frames =
      open_socketcan(options, settings, can.inputs->decoder->database(), &exit_code);
  if (!frames) return {nullptr, exit_code};
  return {std::make_unique<runtime::CanInputSource>(std::move(frames), can.inputs->decoder,
                                                    can.inputs->mapping),
          kExitOk};
}

OpenedInput open_input(const DaemonOptions& options, const Config& config,
                       const ServiceSettings& settings, const Plan& plan) {
  if (!options.replay_log.empty()) return open_replay(options, config);
  if (options.samples_csv.empty()) return open_live(options, config, settings);
  const double timeout_s = settings.daemon.input_timeout_s > 0.0
                               ? settings.daemon.input_timeout_s
                               : runtime::default_samples_timeout_s(plan.tick_rate_hz);
  std::string error;
  auto source = runtime::SamplesCsvSource::open(options.samples_csv, timeout_s, &error);
  if (!source) spdlog::error("{}", error);
  return {std::move(source), source ? kExitOk : kExitUsage};
}

/// --state-file, else daemon.state_file, else $STATE_DIRECTORY/vmassd.state under systemd.
std::string state_path(const DaemonOptions& options, const ServiceSettings& settings) {
  if (!options.state_file.empty()) return options.state_file;
  if (!settings.daemon.state_file.empty()) return settings.daemon.state_file;
  const char* dir = std::getenv("STATE_DIRECTORY");  // systemd StateDirectory=
  if (dir == nullptr || dir[0] == '\0') return "";
  const std::string first(dir);
  return first.substr(0, first.find(':')) + "/vmassd.state";
}

/// Resumes the pipeline from the saved state when it fits. True when restored.
bool restore_state(const std::string& path, runtime::TickStep& step) {
  const StateRestore r = restore_pipeline_state(path, step);
  if (r.refused) spdlog::warn("{}", r.message);
  if (r.restored) spdlog::info("{}", r.message);
  return r.restored;
}

/// What the main thread needs while the others run.
struct MainLoop {
  const sigset_t& signals;
  Shared& shared;
  const StatusContext& ctx;
  SystemdNotifier& notifier;
  const std::string& state_path;
  const PipelineParams& params;
  double persist_interval_s;
};

/// Signals, systemd watchdog and status, periodic state saves, until a stop signal or the end
/// of a recording. Returns the signal (0: the recording ended).
int run_main_loop(const MainLoop& m) {
  const auto persist_ns = static_cast<std::int64_t>(m.persist_interval_s * 1e9);
  std::int64_t next_persist = mono_ns() + persist_ns;
  std::int64_t next_status = mono_ns() + daemon::kNsPerSecond;
  std::int64_t heartbeat_at_ping = -1;
  const timespec poll = daemon::to_timespec(daemon::kPollNs);
  for (;;) {
    siginfo_t info{};
    const int sig = sigtimedwait(&m.signals, &info, &poll);
    if (sig == SIGTERM || sig == SIGINT) return sig;
    if (const int taken = stop_requested(); taken != 0) return taken;
    if (sig == SIGHUP) spdlog::info("SIGHUP ignored: restart the service to reload the config");
    if (m.shared.estimator_done.load(std::memory_order_acquire)) return 0;
    const std::int64_t now = mono_ns();
    const std::int64_t heartbeat = m.shared.heartbeat.load(std::memory_order_acquire);
    if (heartbeat != heartbeat_at_ping &&
        m.notifier.watchdog_due(static_cast<std::uint64_t>(now / 1000))) {
      m.notifier.watchdog();
      m.notifier.watchdog_sent(static_cast<std::uint64_t>(now / 1000));
      heartbeat_at_ping = heartbeat;
    }
    if (now >= next_status) {
      m.notifier.status(daemon::summary_line(daemon::gather_status(m.ctx, m.shared, false)));
      next_status = now + daemon::kNsPerSecond;
    }
    if (now >= next_persist) {
      daemon::save_snapshot(m.state_path, m.shared.snapshot.read(), m.params, m.shared);
      next_persist = now + persist_ns;
    }
  }
}

/// The threads of one run, started in order and joined in order.
struct Threads {
  std::thread publisher, estimator, receive, command;
};

Threads start_threads(runtime::InputSource& source, runtime::TickStep& step, Shared& shared,
                      const Plan& plan, LcmPublisher& publisher, const StatusContext& ctx,
                      lcm::LCM& lcm, const LcmSettings& lcm_settings) {
  Threads t;
  t.command = std::thread(daemon::command_thread, std::ref(lcm),
                          std::cref(lcm_settings.command_channel), std::ref(shared));
  pthread_setname_np(t.command.native_handle(), "vmassd-command");
  t.publisher = std::thread(daemon::publisher_thread, std::ref(publisher), std::ref(shared),
                            std::cref(ctx), lcm_settings.status_period_s);
  t.estimator = std::thread(daemon::estimator_thread, std::ref(source), std::ref(step),
                            std::ref(shared), std::cref(plan));
  if (!plan.max_speed) {
    t.receive =
        std::thread(daemon::receive_thread, std::ref(source), std::ref(shared), std::cref(plan));
    pthread_setname_np(t.receive.native_handle(), "vmassd-receive");
  }
  // Named for top -H, perf and the performance suite's per-thread CPU (15 characters at most).
  pthread_setname_np(t.publisher.native_handle(), "vmassd-publish");
  pthread_setname_np(t.estimator.native_handle(), "vmassd-estimate");
  return t;
}

/// Stops and joins the threads (the estimator first, then the publisher drains its queue).
void join_threads(Threads& t, Shared& shared) {
  shared.stop.store(true);
  if (t.receive.joinable()) t.receive.join();
  t.estimator.join();
  shared.stop_publisher.store(true, std::memory_order_release);
  sem_post(&shared.queue_sem);
  t.publisher.join();
  t.command.join();  // it stops with the publisher
}

/// The orderly stop after the threads joined: the input report, the pipeline flushed (the open
/// Bayes batch closed, as every snapshot saves it) into the final state save, the final status.
/// Returns whether saved.
bool save_final_state(runtime::InputSource& source, runtime::TickStep& step, Shared& shared,
                      const std::string& path, const PipelineParams& params) {
  // The estimator thread has stopped: its input table and pipeline can be used here.
  const std::string input_problems = source.input_report();
  if (!input_problems.empty()) spdlog::info("inputs: {}", input_problems);
  daemon::SnapshotSlot final_slot = shared.snapshot.read();
  if (final_slot.valid && step.flush()) {
    final_slot.snapshot = step.snapshot();
    spdlog::info("open batch flushed into the final state: pairs used {}",
                 final_slot.snapshot.pairs_used);
  }
  return daemon::save_snapshot(path, final_slot, params, shared);
}

void log_start(const StatusContext& ctx, const Plan& plan, const DaemonOptions& options,
               const ServiceSettings& settings, const std::string& state_file,
               std::string_view estimator, const SystemdNotifier& notifier) {
  spdlog::info("vmassd running (version {}): input {}, {} estimator at {} Hz{}, LCM {}{}", kVersion,
               ctx.source_name, estimator, plan.tick_rate_hz,
               plan.recorded ? (plan.max_speed ? std::string(", speed max (log time)")
                                               : ", speed " + options.speed)
                             : std::string(),
               settings.lcm.url,
               state_file.empty() ? std::string(", no state file") : ", state " + state_file);
  if (notifier.watchdog_usec() > 0) {
    spdlog::info("systemd watchdog {} ms: pinging every {} ms while the estimator ticks",
                 notifier.watchdog_usec() / 1000, notifier.watchdog_ping_interval_usec() / 1000);
  }
}

void log_stop(const DaemonStatus& final_status, bool saved, const LcmPublisher& publisher,
              const Shared& shared) {
  spdlog::info(
      "stopped: {}{}; {} estimates published, {} publish failures, {} queue drops, {} input "
      "records late, jitter p50/p99/max {:.0f}/{:.0f}/{:.0f} us; input clock: {} reordered, {} "
      "too late, {} jumps; frames: {} received, {} decoded, {} unknown, {} malformed, {} "
      "dropped, {} bus errors, {} reopens",
      daemon::summary_line(final_status), saved ? ", state saved" : "",
      publisher.estimates_published(), final_status.publish_failures,
      final_status.publish_queue_drops, shared.late_records.load(),
      final_status.timing.jitter_p50_us, final_status.timing.jitter_p99_us,
      final_status.timing.jitter_max_us, final_status.frames_reordered,
      final_status.frames_late_dropped, final_status.time_jumps, final_status.frames_received,
      final_status.frames_decoded, final_status.frames_unknown, final_status.frames_malformed,
      final_status.frames_dropped, final_status.bus_errors, final_status.source_reopens);
}

/// 0 after a good run; 1 when it failed: the recording could not be read to its end, or every
/// LCM publish failed (a daemon that published nothing did not do its job).
int exit_code_of(const runtime::InputSource& source, const Shared& shared) {
  if (const std::string failed = source.read_error(); !failed.empty()) {
    spdlog::error("{}", failed);
    return kExitFailure;
  }
  const std::int64_t failures = shared.publish_failures.load();
  if (shared.published.load() == 0 && failures > 0) {
    spdlog::error("nothing was published on LCM: all {} messages failed", failures);
    return kExitFailure;
  }
  return kExitOk;
}

/// --replay --interface: the frames of other interfaces skipped, logged; a recording played to
/// its end (`ended`) without a frame on the interface is bad input (2). 0 otherwise.
int report_interface(const runtime::LogFrameSource* log, bool ended) {
  const runtime::InterfaceSelection* selection =
      log != nullptr ? log->interface_selection() : nullptr;
  if (selection == nullptr) return kExitOk;
  spdlog::info("{}: interface {}: {} frames of other interfaces skipped", log->path(),
               selection->name(), selection->skipped());
  const std::string none = ended ? log->no_frames_reason() : "";
  if (none.empty()) return kExitOk;
  spdlog::error("{}", none);
  return kExitUsage;
}

/// Everything a run needs once the configuration is read and the input is open.
struct Run {
  const DaemonOptions& options;
  const ServiceSettings& settings;
  Plan plan;
  runtime::InputSource& source;
  const runtime::LogFrameSource* log;  ///< --replay: the source's frames; else null
  lcm::LCM& lcm;
  std::int64_t start_mono_ns;
};

/// Restores the state, starts the threads, serves until a stop, stops in order.
int serve(Run& r, const sigset_t& signals, const PipelineParams& params) {
  runtime::TickStep step(params);
  const std::string state_file = state_path(r.options, r.settings);
  const bool restored =
      !state_file.empty() && !r.options.no_restore && restore_state(state_file, step);
  if (r.plan.recorded && !r.plan.max_speed) {  // at max speed the tick driver reads it
    r.plan.has_first_record = r.source.next_record(0) == runtime::InputSource::Read::kRecord;
    r.plan.t0_us = r.plan.has_first_record ? r.source.record_time_us() : 0;
    if (!r.plan.has_first_record) spdlog::warn("{}: no records", r.source.describe());
  }
  Shared shared(static_cast<std::size_t>(r.settings.daemon.publish_queue));
  const StatusContext ctx{&r.source, r.source.describe(), r.plan.tick_rate_hz, r.start_mono_ns,
                          restored};
  const std::string estimator(step.pipeline().regressor().name());
  LcmPublisher publisher(r.lcm, r.settings.lcm, estimator);
  r.plan.mono0_ns = mono_ns() + 1'000'000;  // first tick 1 ms from now
  if (!r.plan.recorded) {
    // Live: T_0 is CLOCK_REALTIME at tick 0, so the tick clock reads as the wall clock did at
    // start (and live frames' times are their kernel stamps, give or take a few microseconds).
    const daemon::ClockPair now = daemon::read_clocks();
    r.plan.t0_us = now.realtime_us + (r.plan.mono0_ns - now.mono_ns) / 1000;
  }
  Threads threads =
      start_threads(r.source, step, shared, r.plan, publisher, ctx, r.lcm, r.settings.lcm);
  SystemdNotifier notifier;
  notifier.notify("READY=1\nSTATUS=" +
                  daemon::summary_line(daemon::gather_status(ctx, shared, false)));
  log_start(ctx, r.plan, r.options, r.settings, state_file, estimator, notifier);
  const int stop_signal = run_main_loop(
      {signals, shared, ctx, notifier, state_file, params, r.settings.daemon.persist_interval_s});
  if (stop_signal != 0) spdlog::info("{}: stopping", strsignal(stop_signal));
  notifier.notify("STOPPING=1\nSTATUS=stopping");
  join_threads(threads, shared);
  const bool saved = save_final_state(r.source, step, shared, state_file, params);
  const DaemonStatus final_status = daemon::gather_status(ctx, shared, true);
  if (publisher.publish_status(final_status)) shared.published.fetch_add(1);
  log_stop(final_status, saved, publisher, shared);
  const int exit_code = exit_code_of(r.source, shared);
  const int interface_code = report_interface(r.log, stop_signal == 0 && exit_code == kExitOk);
  return exit_code != kExitOk ? exit_code : interface_code;
}

}  // namespace

int run_daemon(const DaemonOptions& options) {
  const std::int64_t start_mono = mono_ns();
  spdlog::info("vmassd {} starting: config {}", kVersion, options.config_path);
  ConfigLoad loaded = load_config(options.config_path);
  if (!loaded.ok()) {
    spdlog::error("{}", loaded.error);
    return kExitUsage;
  }
  ServiceSettingsLoad settings_load = load_service_settings(*loaded.config);
  if (!settings_load.ok()) {
    spdlog::error("{}", settings_load.error);
    return kExitUsage;
  }
  ServiceSettings settings = settings_load.settings;
  if (!options.lcm_url.empty()) {
    if (const std::string e = lcm_url_error(options.lcm_url); !e.empty()) {
      spdlog::error("--lcm-url '{}': {}", options.lcm_url, e);
      return kExitUsage;
    }
    settings.lcm.url = options.lcm_url;
  }
  const std::optional<Plan> plan = make_plan(options, settings, loaded.config->pipeline);
  if (!plan) return kExitUsage;
  lock_memory(settings);
  OpenedInput input = open_input(options, *loaded.config, settings, *plan);
  if (!input.source) return input.exit_code;
  // From here the main loop takes the stop signals (install_stop_signals() ended the process
  // on one until now); blocked before LCM and our threads start, so that they inherit the mask.
  const sigset_t signals = block_stop_signals();
  lcm::LCM lcm(settings.lcm.url);
  if (!lcm.good()) {
    spdlog::error("cannot open LCM at '{}'", settings.lcm.url);
    return kExitFailure;
  }
  Run run{options, settings, *plan, *input.source, input.log, lcm, start_mono};
  return serve(run, signals, loaded.config->pipeline);
}

}  // namespace vmass::service
