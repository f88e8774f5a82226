// vmass-monitor: a terminal view of a running vmassd over LCM, for a headless vehicle PC reached
// over SSH: live mass, interval, status, availability and input health, redrawn in place (ANSI),
// in 80 columns.
//
//   vmass-monitor [--config FILE] [--lcm-url URL] [--estimate-channel C] [--status-channel C]
//                 [--once | --count N | --rates SECONDS] [--timeout SECONDS] [--plain]
//                 [--interval SECONDS]
//
//   (default)      redraw up to 5 times a second until Ctrl-C (in a terminal; --plain, or stdout
//                  not a terminal: one report per second, or per --interval)
//   --once         print one report when an estimate and a status have arrived, then exit
//   --count N      exit after N estimates: in a terminal the live view meanwhile, otherwise
//                  (or --plain) the report once at the end, and every --interval when given
//   --interval S   seconds between reports (live view default 0.2, plain default 1)
//   --rates S      listen S seconds, then print per-channel message rates and how many fields
//                  were not finite (exit 1 when a field was not finite or nothing arrived)
//   --timeout S    give up (exit 1) when nothing arrived within S seconds (default 10 for
//                  --once/--count, none otherwise)
//
// The rates in the report are those of the last 5 s (three status periods when longer:
// recent_rate.hpp). Once the longitudinal block has taken no pair for 30 s of vmassd's ticks,
// the report says which verdicts those ticks had instead (from the statuses of the last 3 min:
// verdict_history.hpp). When no estimate has arrived for three status periods (3 s at least),
// the report's second line says so ("no estimate for 12 s: is vmassd running?"); --once and
// --count then end with exit 1. --rates measures over its whole listening time.
#include <time.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>
#include <vmass/mass_estimate_t.hpp>
#include <vmass/status_t.hpp>

#include "config_lcm_settings.hpp"
#include "exit_code.hpp"
#include "monitor_report.hpp"
#include "recent_rate.hpp"
#include "verdict_history.hpp"
#include "vmass/config/config.hpp"
#include "vmass/service/service_config.hpp"

namespace {

using Clock = std::chrono::steady_clock;

/// Draws `text` over the previous view: home, each line cleared to its end, then whatever is
/// below cleared.
void redraw(const std::string& text) {
  std::string screen = "\x1b[H";
  for (char c : text) screen += c == '\n' ? std::string("\x1b[K\n") : std::string(1, c);
  screen += "\x1b[J";
  std::fputs(screen.c_str(), stdout);
}
volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }

int nonfinite(const vmass::mass_estimate_t& m) {
  int n = 0;
  for (double v :
       {m.mass_kg, m.mass_std_kg, m.mass_ci_low_kg, m.mass_ci_high_kg, m.mu_n, m.initial_mass_kg,
        m.longitudinal_availability, m.lateral_availability, m.learnt_scale, m.learnt_scale_std}) {
    n += std::isfinite(v) ? 0 : 1;
  }
  return n;
}

int nonfinite(const vmass::status_t& s) {
  int n = 0;
  for (double v :
       {s.uptime_s, s.mass_kg, s.tick_rate_hz, s.jitter_p50_us, s.jitter_p99_us, s.jitter_max_us,
        s.wake_latency_max_us, s.tick_compute_max_us, s.learnt_scale, s.learnt_scale_std}) {
    n += std::isfinite(v) ? 0 : 1;
  }
  for (double v : s.input_age_s) n += std::isfinite(v) ? 0 : 1;
  return n;
}

std::int64_t realtime_us() {
  timespec ts{};
  ::clock_gettime(CLOCK_REALTIME, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
}

double seconds_between(Clock::time_point from, Clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

struct ChannelStats {
  explicit ChannelStats(double window_s) : recent(window_s) {}
  long count = 0;
  long nonfinite_fields = 0;
  Clock::time_point first, last;
  vmass::monitor::RecentRate recent;  ///< the report's rate; seconds since the monitor started
  /// Since the first message (--rates).
  double rate_hz() const {
    const double span = seconds_between(first, last);
    return count > 1 && span > 0.0 ? static_cast<double>(count - 1) / span : 0.0;
  }
};

class Monitor {
 public:
  /// `status_period_s`: vmassd's (lcm.status_period_s), which sets the rate window and how long
  /// a silence means the daemon is gone.
  explicit Monitor(double status_period_s)
      : status_period_s_(status_period_s),
        estimates_(vmass::monitor::rate_window_s(status_period_s)),
        statuses_(vmass::monitor::rate_window_s(status_period_s)) {}

  void on_estimate(const lcm::ReceiveBuffer*, const std::string&,
                   const vmass::mass_estimate_t* msg) {
    estimate_ = *msg;
    record(&estimates_, nonfinite(*msg));
  }
  void on_status(const lcm::ReceiveBuffer*, const std::string&, const vmass::status_t* msg) {
    status_ = *msg;
    record(&statuses_, nonfinite(*msg));
    verdicts_.add(since_start(Clock::now()), *msg);
  }

  /// What was received last, laid out for 80 columns (monitor_report.hpp), with the rates of
  /// the last seconds, a warning when the estimates fell silent, why no pair came lately and
  /// the last command's age.
  std::string report(const std::string& url) {
    const double now = since_start(Clock::now());
    vmass::monitor::ReportContext context;
    context.no_pair = verdicts_.no_pair();
    context.now_utime = realtime_us();
    return vmass::monitor::monitor_report(
        url, estimates_.recent.rate_hz(now), statuses_.recent.rate_hz(now),
        estimate_ ? &*estimate_ : nullptr, status_ ? &*status_ : nullptr, silence(now), context);
  }

  /// How long the channels have been silent at `now_s` (seconds since the start).
  vmass::monitor::Silence silence(double now_s) const {
    vmass::monitor::Silence s;
    s.estimate_s = estimates_.count > 0 ? estimates_.recent.silent_s(now_s) : now_s;
    s.status_s = statuses_.recent.silent_s(now_s);
    s.limit_s =
        vmass::monitor::silence_limit_s(status_period_s_, estimates_.recent.mean_interval_s());
    return s;
  }

  /// Estimates arrived, then none for longer than the silence limit: vmassd is gone.
  std::string gone_message() const {
    if (estimates_.count == 0) return "";
    return vmass::monitor::silence_message(silence(since_start(Clock::now())));
  }

  double since_start(Clock::time_point t) const { return seconds_between(start_, t); }

  const ChannelStats& estimates() const { return estimates_; }
  const ChannelStats& statuses() const { return statuses_; }
  bool complete() const { return estimate_.has_value() && status_.has_value(); }

 private:
  void record(ChannelStats* c, int bad) {
    const Clock::time_point now = Clock::now();
    if (c->count == 0) c->first = now;
    c->last = now;
    ++c->count;
    c->nonfinite_fields += bad;
    c->recent.add(since_start(now));
  }

  Clock::time_point start_ = Clock::now();
  double status_period_s_;
  std::optional<vmass::mass_estimate_t> estimate_;
  std::optional<vmass::status_t> status_;
  ChannelStats estimates_, statuses_;
  vmass::monitor::VerdictHistory verdicts_;
};

struct Options {
  std::string config_path, url, estimate_channel, status_channel;
  bool once = false, plain = false;
  long count = 0;
  double rates_s = 0.0, timeout_s = -1.0, interval_s = 0.0;
};

std::optional<int> parse_options(int argc, char** argv, Options* o) {
  CLI::App app{"vmass-monitor: live view of vmassd's LCM output in a terminal"};
  app.add_option("--config", o->config_path, "vmass config (for its lcm: URL and channel names)");
  app.add_option("--lcm-url", o->url,
                 "LCM URL (default: the config's lcm.url, else vmassd's default "
                 "udpm://239.255.76.67:7667?ttl=0)");
  app.add_option("--estimate-channel", o->estimate_channel, "default VMASS_ESTIMATE");
  app.add_option("--status-channel", o->status_channel, "default VMASS_STATUS");
  auto* once_opt = app.add_flag("--once", o->once, "print one report and exit");
  auto* count_opt =
      app.add_option("--count", o->count, "exit after N estimates")->check(CLI::PositiveNumber);
  auto* rates_opt =
      app.add_option("--rates", o->rates_s, "listen this many seconds, print message rates, exit")
          ->check(CLI::PositiveNumber);
  app.add_option("--timeout", o->timeout_s, "exit 1 when nothing arrives within this many seconds");
  app.add_flag("--plain", o->plain, "no ANSI redraw (default when stdout is not a terminal)");
  app.add_option("--interval", o->interval_s,
                 "seconds between reports (live view 0.2, plain 1; with --count --plain: only "
                 "when given)")
      ->check(CLI::PositiveNumber);
  once_opt->excludes(count_opt)->excludes(rates_opt);
  count_opt->excludes(rates_opt);
  return vmass::tools::parse_command_line(app, argc, argv);
}

/// The LCM URL and channels: the config's lcm: section, then the flags. False on a config error.
bool lcm_settings_for(const Options& o, vmass::service::LcmSettings* out) {
  if (!vmass::tools::load_lcm_settings(o.config_path, "vmass-monitor", out)) return false;
  if (!o.url.empty()) out->url = o.url;
  if (!o.estimate_channel.empty()) out->estimate_channel = o.estimate_channel;
  if (!o.status_channel.empty()) out->status_channel = o.status_channel;
  return true;
}

/// How the reports come out.
struct Mode {
  bool batch = false;     ///< --once, --count or --rates: the run ends by itself
  bool ansi = false;      ///< the live view: by default, and with --count, on a terminal
  bool periodic = false;  ///< reports every interval: the live view, the default, --count with
                          ///< --interval
  Clock::duration interval{};
};

Mode mode_for(Options* o) {
  Mode m;
  m.batch = o->once || o->count > 0 || o->rates_s > 0.0;
  if (o->timeout_s < 0.0 && (o->once || o->count > 0)) o->timeout_s = 10.0;
  m.ansi = !o->plain && !o->once && o->rates_s <= 0.0 && ::isatty(STDOUT_FILENO);
  m.periodic = m.ansi || !m.batch || (o->count > 0 && o->interval_s > 0.0);
  if (o->interval_s <= 0.0) o->interval_s = m.ansi ? 0.2 : 1.0;
  m.interval =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o->interval_s));
  return m;
}

/// Handles LCM messages and prints reports until the run ends. An exit code when it ended on
/// a timeout or on vmassd's silence (1), nullopt when it ended as asked.
std::optional<int> watch(lcm::LCM& lcm, Monitor& monitor, const Options& o, const Mode& m,
                         const vmass::service::LcmSettings& settings) {
  const Clock::time_point start = Clock::now();
  Clock::time_point next_draw = start;
  if (m.ansi) std::fputs("\x1b[2J", stdout);
  while (!g_stop) {
    lcm.handleTimeout(50);
    const Clock::time_point now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start).count();
    if (o.rates_s > 0.0 && elapsed >= o.rates_s) break;
    if (o.once && monitor.complete()) break;
    if (o.count > 0 && monitor.estimates().count >= o.count) break;
    const bool anything = monitor.estimates().count > 0 || monitor.statuses().count > 0;
    if (o.timeout_s > 0.0 && elapsed >= o.timeout_s && !anything) {
      std::fprintf(stderr, "vmass-monitor: nothing received on %s / %s within %.1f s\n",
                   settings.estimate_channel.c_str(), settings.status_channel.c_str(), o.timeout_s);
      return 1;
    }
    if (o.timeout_s > 0.0 && elapsed >= o.timeout_s && (o.once || o.count > 0)) {
      std::fprintf(stderr, "vmass-monitor: timed out after %.1f s\n", o.timeout_s);
      std::fputs(monitor.report(settings.url).c_str(), stdout);
      return 1;
    }
    if (o.once || o.count > 0) {
      if (const std::string gone = monitor.gone_message(); !gone.empty()) {
        std::fprintf(stderr, "vmass-monitor: %s\n", gone.c_str());
        std::fputs(monitor.report(settings.url).c_str(), stdout);
        return 1;
      }
    }
    if (m.periodic && now >= next_draw && (m.ansi || anything)) {
      const std::string text = monitor.report(settings.url);
      if (m.ansi) {
        redraw(text);
      } else {
        std::fputs((text + "\n").c_str(), stdout);
      }
      std::fflush(stdout);
      next_draw = now + m.interval;
    }
  }
  return std::nullopt;
}

/// --rates: messages and rates per channel over the whole listening time; 0 when both arrived,
/// finite.
int print_rates(const Monitor& monitor, const vmass::service::LcmSettings& settings) {
  const ChannelStats& e = monitor.estimates();
  const ChannelStats& s = monitor.statuses();
  std::printf("%s messages=%ld rate_hz=%.3f nonfinite_fields=%ld\n",
              settings.estimate_channel.c_str(), e.count, e.rate_hz(), e.nonfinite_fields);
  std::printf("%s messages=%ld rate_hz=%.3f nonfinite_fields=%ld\n",
              settings.status_channel.c_str(), s.count, s.rate_hz(), s.nonfinite_fields);
  const bool ok = e.count > 0 && s.count > 0 && e.nonfinite_fields == 0 && s.nonfinite_fields == 0;
  return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const auto code = parse_options(argc, argv, &o)) return *code;
  vmass::service::LcmSettings settings;
  if (!lcm_settings_for(o, &settings)) return vmass::tools::kExitUsage;
  const Mode mode = mode_for(&o);
  lcm::LCM lcm(settings.url);
  if (!lcm.good()) {
    std::fprintf(stderr, "vmass-monitor: cannot open LCM at '%s'\n", settings.url.c_str());
    return vmass::tools::kExitFailure;
  }
  Monitor monitor(settings.status_period_s);
  lcm.subscribe(settings.estimate_channel, &Monitor::on_estimate, &monitor);
  lcm.subscribe(settings.status_channel, &Monitor::on_status, &monitor);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  if (const auto code = watch(lcm, monitor, o, mode, settings)) return *code;
  if (o.rates_s > 0.0) return print_rates(monitor, settings);
  if (mode.ansi) {
    redraw(monitor.report(settings.url));  // the final view stays, the cursor below it
  } else if (mode.batch) {
    std::fputs(monitor.report(settings.url).c_str(), stdout);
  }
  return 0;
}
