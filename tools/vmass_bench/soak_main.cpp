// vmass-soak: many hours of driving through vmassd, accelerated. A frame generator (not a file:
// 24 hours at a full bus are about 700 million frames) loops a drive's candump -l log with its
// time stamps moved on by the log's span each loop, adds filler frames of ids the DBC does not
// know (as a real powertrain bus carries them) and writes the candump -l text into a pipe that
// the daemon replays from its standard input at log time, as fast as it goes:
//
//   vmass-soak --log LOG --dbc DBC [--hours H] [--filler-fps N] [--daemon-log PATH]
//              -- vmassd --config C --replay /dev/stdin --speed max --lcm-url memq://
//
// While it runs it samples the daemon's resident memory once a second; at the end it reads the
// daemon's final log line (ticks, overruns, publish failures, queue drops, late records, clock
// repairs, frame counters). Prints one JSON object: memory at start (after the first simulated
// hour, or a tenth of a shorter run), at the end and at its peak, frames written and the daemon's
// counts. Exit codes: 0 the daemon ran to the end of the stream and stopped cleanly, 1 it died or
// its log lacks the final line, 2 usage or an input that cannot be read.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iostream>
#include <memory>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "bus_feed.hpp"
#include "daemon_process.hpp"
#include "exit_code.hpp"
#include "proc_stats.hpp"
#include "vmass/can/candump.hpp"
#include "vmass/can/dbc.hpp"
#include "vmass/can/decoder.hpp"
#include "vmass/json/json.hpp"

namespace {

using namespace vmass;

/// A measured figure, at the 6 significant digits a stream prints by default.
json::Json figure(double v) { return json::significant(v, 6); }

struct Options {
  std::string log, dbc, daemon_log = "/tmp/vmass-soak-daemon.log";
  double hours = 24.0;
  double filler_fps = 7500.0;  // with a drive's ~600 frames/s: a 1 Mbit/s bus near its limit
  std::vector<std::string> command;
};

/// The generated bus: the drive looped end to end, merged in time order with filler frames
/// spread evenly over each filler period.
class SoakStream {
 public:
  SoakStream(std::vector<can::CanFrame> drive, std::vector<std::uint32_t> filler_ids,
             double filler_fps)
      : drive_(std::move(drive)), filler_ids_(std::move(filler_ids)) {
    const std::int64_t t0 = drive_.front().time_us;
    for (can::CanFrame& f : drive_) f.time_us -= t0;
    span_us_ = drive_.back().time_us + 10'000;  // a tick's gap between loops
    filler_step_us_ = filler_ids_.empty() || filler_fps <= 0.0
                          ? -1
                          : std::max<std::int64_t>(1, std::llround(1e6 / filler_fps));
  }

  /// The next frame in time order, with time stamps from `start_us` on.
  const can::CanFrame& next() {
    const std::int64_t drive_t = offset_us_ + drive_[next_drive_].time_us;
    if (filler_step_us_ > 0 && next_filler_us_ < drive_t) return next_filler();
    current_ = drive_[next_drive_];
    current_.time_us = start_us_ + drive_t;
    if (++next_drive_ == drive_.size()) {
      next_drive_ = 0;
      offset_us_ += span_us_;
    }
    ++drive_frames_;
    return current_;
  }

  std::int64_t simulated_us() const { return offset_us_ + drive_[next_drive_].time_us; }
  std::uint64_t drive_frames() const { return drive_frames_; }
  std::uint64_t filler_frames() const { return filler_frames_; }

 private:
  const can::CanFrame& next_filler() {
    current_ = can::CanFrame{};
    current_.time_us = start_us_ + next_filler_us_;
    current_.id = filler_ids_[filler_index_];
    current_.len = 8;
    for (std::uint8_t i = 0; i < 8; ++i) {
      current_.data[i] = static_cast<std::uint8_t>(filler_frames_ >> (i % 4 * 8));
    }
    filler_index_ = (filler_index_ + 1) % filler_ids_.size();
    next_filler_us_ += filler_step_us_;
    ++filler_frames_;
    return current_;
  }

  static constexpr std::int64_t start_us_ = 1'700'000'000'000'000;  // a plausible wall clock
  std::vector<can::CanFrame> drive_;
  std::vector<std::uint32_t> filler_ids_;
  std::int64_t span_us_ = 0, filler_step_us_ = -1;
  std::size_t next_drive_ = 0, filler_index_ = 0;
  std::int64_t offset_us_ = 0, next_filler_us_ = 0;
  std::uint64_t drive_frames_ = 0, filler_frames_ = 0;
  can::CanFrame current_;
};

std::string make_stream(const Options& o, std::unique_ptr<SoakStream>* stream) {
  std::vector<can::CanFrame> frames;
  if (std::string e = bench::read_log_frames(o.log, &frames); !e.empty()) return e;
  can::DbcParseResult parsed = can::load_dbc_file(o.dbc);
  std::string error;
  auto decoder = can::Decoder::compile(std::move(parsed.database), &error);
  if (!decoder) return o.dbc + ": " + error;
  auto filler = bench::unknown_ids(
      40, [&](std::uint32_t id) { return decoder->find_message(id, false) >= 0; });
  *stream = std::make_unique<SoakStream>(std::move(frames), std::move(filler), o.filler_fps);
  return "";
}

/// Starts the command with the pipe's read end as its standard input, its output and errors
/// into the daemon log.
pid_t start_daemon(const Options& o, int read_fd) {
  return bench::start_command(o.command, o.daemon_log, read_fd, STDIN_FILENO);
}

/// Writes all of buf; false when the daemon closed its end.
bool write_all(int fd, const char* buf, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, buf, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    buf += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

struct MemoryTrace {
  long start_kb = -1, end_kb = -1, min_kb = -1, max_kb = -1;
  void add(long kb, bool past_first_hour) {
    if (kb <= 0) return;
    end_kb = kb;
    if (!past_first_hour) return;
    if (start_kb < 0) start_kb = min_kb = max_kb = kb;
    min_kb = std::min(min_kb, kb);
    max_kb = std::max(max_kb, kb);
  }
};

struct FeedResult {
  bool complete = false;  ///< every frame written
  double wall_s = 0.0;
  MemoryTrace memory;
};

/// Feeds the whole soak into fd, sampling the daemon's memory once a second.
FeedResult feed(SoakStream& stream, const Options& o, int fd, pid_t pid) {
  constexpr std::size_t kChunk = 1 << 20;
  const auto end_us = static_cast<std::int64_t>(o.hours * 3600e6);
  // "Start" memory: once warm (the first simulated hour, or a tenth of a shorter run).
  const std::int64_t warm_us = std::min<std::int64_t>(3600'000'000, end_us / 10);
  std::vector<char> buf(kChunk + 256);
  std::size_t used = 0;
  FeedResult result;
  const auto t0 = std::chrono::steady_clock::now();
  auto next_sample = t0;
  while (stream.simulated_us() < end_us) {
    used += can::format_candump_line(stream.next(), "can0", buf.data() + used, 256);
    if (used < kChunk) continue;
    if (!write_all(fd, buf.data(), used)) return result;
    used = 0;
    if (const auto now = std::chrono::steady_clock::now(); now >= next_sample) {
      result.memory.add(bench::read_memory(pid).rss_kb, stream.simulated_us() > warm_us);
      next_sample = now + std::chrono::seconds(1);
    }
  }
  result.complete = write_all(fd, buf.data(), used);
  result.memory.add(bench::read_memory(pid).rss_kb, true);
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

/// "name": N members for every "N words" counter of the daemon's final "stopped:" line;
/// null when the line is absent.
json::Json final_counters_json(const std::string& log) {
  const std::string line = bench::stopped_line(log);
  if (line.empty()) return nullptr;
  static const std::regex counter(
      R"((\d+) (ticks|overruns|estimates published|publish failures|queue drops|input records late|reordered|too late|jumps|received|decoded|unknown|malformed|dropped|bus errors|reopens))");
  json::Json out = json::Json::object();
  for (std::sregex_iterator it(line.begin(), line.end(), counter), end; it != end; ++it) {
    std::string name = (*it)[2].str();
    for (char& c : name) c = c == ' ' ? '_' : c;
    out[name] = std::stoull((*it)[1].str());
  }
  return out;
}

int parse(int argc, char** argv, Options* o) {
  CLI::App app{"vmass-soak: hours of simulated driving through vmassd, as fast as it goes"};
  app.add_option("--log", o->log, "the drive's candump -l log (looped)")->required();
  app.add_option("--dbc", o->dbc, "the vehicle's DBC (filler ids are ids it does not know)")
      ->required();
  app.add_option("--hours", o->hours, "simulated hours of driving")->check(CLI::PositiveNumber);
  app.add_option("--filler-fps", o->filler_fps, "filler frames per simulated second")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--daemon-log", o->daemon_log, "the daemon's standard error");
  app.add_option("command", o->command, "the daemon command (replays its standard input)")
      ->required();
  const auto code = vmass::tools::parse_command_line(app, argc, argv);
  return code ? *code : -1;
}

void print_report(const Options& o, const SoakStream& stream, const FeedResult& fed,
                  const json::Json& counters) {
  const std::uint64_t frames = stream.drive_frames() + stream.filler_frames();
  json::Json report = {
      {"simulated_hours", figure(static_cast<double>(stream.simulated_us()) / 3600e6)},
      {"frames_written", frames},
      {"drive_frames", stream.drive_frames()},
      {"filler_frames", stream.filler_frames()},
      {"wall_s", figure(fed.wall_s)},
      {"frames_per_s", figure(static_cast<double>(frames) / std::max(1e-3, fed.wall_s))},
      {"rss_start_kb", fed.memory.start_kb},
      {"rss_end_kb", fed.memory.end_kb},
      {"rss_min_kb", fed.memory.min_kb},
      {"rss_max_kb", fed.memory.max_kb},
      {"hours_requested", figure(o.hours)}};
  report.update(counters);
  std::cout << json::dump(report) << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const int rc = parse(argc, argv, &o); rc >= 0) return rc;
  std::unique_ptr<SoakStream> stream;
  if (const std::string e = make_stream(o, &stream); !e.empty()) {
    std::cerr << "vmass-soak: " << e << "\n";
    return 2;
  }
  signal(SIGPIPE, SIG_IGN);  // a daemon that dies shows as a failed write, not our death
  int pipe_fds[2];
  if (pipe2(pipe_fds, O_CLOEXEC) != 0) return 1;
  (void)fcntl(pipe_fds[1], F_SETPIPE_SZ, 1 << 20);
  const pid_t pid = start_daemon(o, pipe_fds[0]);
  close(pipe_fds[0]);
  const FeedResult fed = feed(*stream, o, pipe_fds[1], pid);
  close(pipe_fds[1]);  // end of stream: the daemon finishes its replay and stops
  int status = 0;
  waitpid(pid, &status, 0);
  const std::string log = bench::read_text(o.daemon_log);
  const json::Json counters = final_counters_json(log);
  if (!fed.complete || counters.is_null() || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::cerr << "vmass-soak: the daemon "
              << (fed.complete ? "did not stop cleanly" : "stopped reading the stream")
              << "; its log (" << o.daemon_log << "), last part:\n"
              << log.substr(log.size() > 4000 ? log.size() - 4000 : 0);
    return 1;
  }
  print_report(o, *stream, fed, counters);
  return 0;
}
