// vmass-bench-daemon: vmassd's cost at a realistic bus load, whole process. Starts the daemon
// command given after `--` with one end of a socketpair as its descriptor 3 (the command reads
// it with `vmassd --can-fd 3`: the SocketCAN reader's fd seam, so the receive path is counted),
// once it runs feeds the bus through the other end (bus_feed.hpp: a drive's log at its pace plus
// filler frames of ids the DBC does not know), and after a warm-up measures over a window: CPU per
// thread and in all (/proc schedstat), resident memory, the load average; then stops the daemon
// with SIGTERM and reads its tick jitter p50/p99/max and overruns from its final log line.
//
//   vmass-bench-daemon --log LOG --dbc DBC [--filler-fps N] [--warmup S] [--seconds S]
//                      [--daemon-log PATH] -- COMMAND [ARGS...]
//
// Prints one JSON object. Exit codes: 0 measured, 1 the daemon died or its log lacks the final
// line, 2 usage or an input that cannot be read.
#include <fcntl.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "bus_feed.hpp"
#include "daemon_process.hpp"
#include "exit_code.hpp"
#include "proc_stats.hpp"
#include "vmass/can/dbc.hpp"
#include "vmass/can/decoder.hpp"
#include "vmass/json/json.hpp"

namespace {

using namespace vmass;

/// A measured figure, at the 6 significant digits a stream prints by default.
json::Json figure(double v) { return json::significant(v, 6); }

struct Options {
  std::string log, dbc, daemon_log = "/tmp/vmass-bench-daemon.log";
  double filler_fps = 2500.0;
  double warmup_s = 5.0;
  double seconds = 60.0;
  std::vector<std::string> command;
};

/// The bus: the log's frames and filler ids the DBC does not know; "" or why not.
std::string make_feed(const Options& o, std::unique_ptr<bench::BusFeed>* feed) {
  std::vector<can::CanFrame> frames;
  if (std::string e = bench::read_log_frames(o.log, &frames); !e.empty()) return e;
  can::DbcParseResult parsed = can::load_dbc_file(o.dbc);
  std::string error;
  auto decoder = can::Decoder::compile(std::move(parsed.database), &error);
  if (!decoder) return o.dbc + ": " + error;
  constexpr int kFillerPeriodMs = 20;
  const int ids = static_cast<int>(std::lround(o.filler_fps * kFillerPeriodMs / 1000.0));
  auto filler = bench::unknown_ids(
      ids, [&](std::uint32_t id) { return decoder->find_message(id, false) >= 0; });
  *feed = std::make_unique<bench::BusFeed>(std::move(frames), std::move(filler), kFillerPeriodMs);
  return "";
}

/// Starts the command with `bus_fd` as its descriptor 3 (time-stamped by the kernel on receipt,
/// as a CAN socket's records are) and its standard output and error into the daemon log.
pid_t start_daemon(const Options& o, int bus_fd) {
  const int one = 1;
  (void)setsockopt(bus_fd, SOL_SOCKET, SO_TIMESTAMP, &one, sizeof one);
  ::unlink(o.daemon_log.c_str());  // not a previous run's "vmassd running" line
  return bench::start_command(o.command, o.daemon_log, bus_fd, 3);
}

bool alive(pid_t pid) { return waitpid(pid, nullptr, WNOHANG) == 0; }

/// Waits up to 30 s for the daemon's "vmassd running" line (configuration read, input open):
/// the bus is fed from then on, so that no frame is dropped while it starts. False when it died
/// or never got there.
bool wait_until_running(pid_t pid, const std::string& daemon_log) {
  for (int i = 0; i < 600 && alive(pid); ++i) {
    if (bench::read_text(daemon_log).find("vmassd running") != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

/// SIGTERM, then SIGKILL after 10 s. True when it stopped by itself after SIGTERM.
bool stop_daemon(pid_t pid) {
  kill(pid, SIGTERM);
  for (int i = 0; i < 200; ++i) {
    if (waitpid(pid, nullptr, WNOHANG) == pid) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  return false;
}

/// The numbers of the daemon's final log line ("stopped: ... N ticks[, M overruns]; ... jitter
/// p50/p99/max a/b/c us"), as JSON members (overruns null before a mass is known: the line
/// leaves them out then); null when absent.
json::Json final_line_json(const std::string& log) {
  static const std::regex ticks(R"((\d+) ticks(, (\d+) overruns)?)");
  static const std::regex jitter(R"(jitter p50/p99/max (\d+)/(\d+)/(\d+) us)");
  std::smatch t, j;
  const std::string line = bench::stopped_line(log);
  if (line.empty()) return nullptr;
  if (!std::regex_search(line, t, ticks) || !std::regex_search(line, j, jitter)) return nullptr;
  return {{"ticks", std::stoull(t[1].str())},
          {"overruns", t[3].matched ? json::Json(std::stoull(t[3].str())) : json::Json()},
          {"jitter_p50_us", std::stoull(j[1].str())},
          {"jitter_p99_us", std::stoull(j[2].str())},
          {"jitter_max_us", std::stoull(j[3].str())}};
}

json::Json threads_json(const std::map<std::string, bench::ThreadCpu>& before,
                        const std::map<std::string, bench::ThreadCpu>& after, double window_s,
                        double* total_percent) {
  json::Json out = json::Json::object();
  *total_percent = 0.0;
  for (const auto& [name, cpu] : after) {
    const auto b = before.find(name);
    const bench::ThreadCpu zero;
    const bench::ThreadCpu& from = b == before.end() ? zero : b->second;
    const double percent = 100.0 * static_cast<double>(cpu.run_ns - from.run_ns) / 1e9 / window_s;
    const double wakeups = static_cast<double>(cpu.slices - from.slices) / window_s;
    *total_percent += percent;
    out[name] = {{"cpu_percent", figure(percent)}, {"scheduled_per_s", figure(wakeups)}};
  }
  return out;
}

int parse(int argc, char** argv, Options* o) {
  CLI::App app{"vmass-bench-daemon: vmassd's CPU, memory and jitter at a realistic bus load"};
  app.add_option("--log", o->log, "the drive's candump -l log")->required();
  app.add_option("--dbc", o->dbc, "the vehicle's DBC (filler ids are ids it does not know)")
      ->required();
  app.add_option("--filler-fps", o->filler_fps, "filler frames per second");
  app.add_option("--warmup", o->warmup_s, "seconds before the window");
  app.add_option("--seconds", o->seconds, "the measured window");
  app.add_option("--daemon-log", o->daemon_log, "the daemon's standard error");
  app.add_option("command", o->command, "the daemon command (reads --can-fd 3)")->required();
  const auto code = vmass::tools::parse_command_line(app, argc, argv);
  return code ? *code : -1;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const int rc = parse(argc, argv, &o); rc >= 0) return rc;
  std::unique_ptr<bench::BusFeed> feed;
  if (const std::string e = make_feed(o, &feed); !e.empty()) {
    std::cerr << "vmass-bench-daemon: " << e << "\n";
    return 2;
  }
  int sv[2];
  if (socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, sv) != 0) return 1;
  const int sndbuf = 1 << 20;  // room for a CAN socket's receive queue
  setsockopt(sv[0], SOL_SOCKET, SO_SNDBUF, &sndbuf, sizeof sndbuf);
  const pid_t pid = start_daemon(o, sv[1]);
  close(sv[1]);
  if (!wait_until_running(pid, o.daemon_log)) {
    if (alive(pid)) stop_daemon(pid);
    std::cerr << "vmass-bench-daemon: the daemon did not start; its log (" << o.daemon_log << "):\n"
              << bench::read_text(o.daemon_log);
    return 1;
  }
  std::atomic<bool> stop{false};
  std::thread feeder([&] { feed->run(sv[0], stop); });
  std::this_thread::sleep_for(std::chrono::duration<double>(o.warmup_s));
  const auto before = bench::read_thread_cpu(pid);
  const bench::Memory memory_at_start = bench::read_memory(pid);
  const auto t0 = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(std::chrono::duration<double>(o.seconds));
  const auto after = bench::read_thread_cpu(pid);
  const double window_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const bench::Memory memory = bench::read_memory(pid);
  const double load = bench::read_load_average();
  stop = true;  // the bus first: what a stopping daemon leaves unread is not a drop
  feeder.join();
  const bool was_alive = alive(pid);
  const bool stopped = was_alive && stop_daemon(pid);
  close(sv[0]);
  const json::Json final_line = final_line_json(bench::read_text(o.daemon_log));
  if (!stopped || final_line.is_null()) {
    std::cerr << "vmass-bench-daemon: the daemon " << (was_alive ? "did not stop" : "died")
              << "; its log (" << o.daemon_log << "):\n"
              << bench::read_text(o.daemon_log);
    return 1;
  }
  double cpu_percent = 0.0;
  const json::Json threads = threads_json(before, after, window_s, &cpu_percent);
  const bench::BusFeedStats& s = feed->stats();
  const double sent = static_cast<double>(s.log_frames + s.filler_frames);
  const double run_s = std::max(1e-3, s.seconds);
  json::Json report = {{"window_s", figure(window_s)},
                       {"cpu_percent", figure(cpu_percent)},
                       {"threads", threads},
                       {"rss_start_kb", memory_at_start.rss_kb},
                       {"rss_kb", memory.rss_kb},
                       {"hwm_kb", memory.hwm_kb},
                       {"frames_per_s", figure(sent / run_s)},
                       {"log_frames_per_s", figure(static_cast<double>(s.log_frames) / run_s)},
                       {"filler_frames_per_s", figure(feed->filler_frames_per_s())},
                       {"frames_dropped", s.dropped},
                       {"load_average", figure(load)}};
  report.update(final_line);
  std::cout << json::dump(report) << "\n";
  return 0;
}
