#include "vmass/runtime/converted_log_frame_source.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "vmass/io/sibling_program.hpp"

extern char** environ;  // NOLINT(readability-redundant-declaration): POSIX, for posix_spawn

namespace vmass::runtime {
namespace {

constexpr std::string_view kErrorPrefix = "#!error ";
constexpr std::string_view kFatalPrefix = "#!fatal ";

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

std::string env_or_empty(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr ? std::string(v) : std::string();
}

/// Starts `argv` with its standard output on a pipe; the read end, or null (*error set).
FILE* spawn_reading(const std::vector<std::string>& args, pid_t* child, std::string* error) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) {
    *error = std::string("pipe: ") + std::strerror(errno);
    return nullptr;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const int rc = posix_spawnp(child, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  if (rc != 0) {
    ::close(fds[0]);
    *error = "cannot run " + args.front() + ": " + std::strerror(rc);
    return nullptr;
  }
  return ::fdopen(fds[0], "r");
}

}  // namespace

std::string ConvertedLogFrameSource::converter_path() {
  if (std::string named = env_or_empty("VMASS_LOG_CONVERT"); !named.empty()) return named;
  return io::sibling_program("vmass-log-convert");
}

ConvertedLogFrameSource::ConvertedLogFrameSource(const std::string& path, can::LogFormat format,
                                                 FILE* out, pid_t child)
    : LogFrameSource(path, format), out_(out), child_(child) {}

std::unique_ptr<ConvertedLogFrameSource> ConvertedLogFrameSource::open(const std::string& path,
                                                                       can::LogFormat format,
                                                                       std::string* error) {
  std::vector<std::string> args;
  if (std::string python = env_or_empty("VMASS_PYTHON"); !python.empty()) args.push_back(python);
  args.push_back(converter_path());
  args.push_back(path);
  pid_t child = -1;
  std::string why;
  FILE* out = spawn_reading(args, &child, &why);
  if (out == nullptr) {
    if (error) *error = path + ": " + std::string(can::log_format_name(format)) + ": " + why;
    return nullptr;
  }
  std::unique_ptr<ConvertedLogFrameSource> source(
      new ConvertedLogFrameSource(path, format, out, child));
  // The converter says first when it cannot read the file at all.
  source->have_line_ = source->next_line();
  if (source->have_line_ && starts_with(source->line_, kFatalPrefix)) {
    if (error) *error = path + ": " + source->line_.substr(kFatalPrefix.size());
    return nullptr;
  }
  return source;
}

ConvertedLogFrameSource::~ConvertedLogFrameSource() {
  if (out_ != nullptr) std::fclose(out_);  // a converter still writing gets EPIPE and ends
  if (child_ > 0) {
    ::kill(child_, SIGTERM);
    int status = 0;
    ::waitpid(child_, &status, 0);
  }
}

bool ConvertedLogFrameSource::next_line() {
  line_.clear();
  int c = 0;
  while ((c = std::getc(out_)) != EOF && c != '\n') line_.push_back(static_cast<char>(c));
  return c != EOF || !line_.empty();
}

void ConvertedLogFrameSource::finish() {
  int status = 0;
  if (child_ <= 0 || ::waitpid(child_, &status, 0) != child_) return;
  child_ = -1;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return;
  set_problem(converter_path() + " ended with " +
              (WIFEXITED(status) ? "status " + std::to_string(WEXITSTATUS(status))
                                 : "signal " + std::to_string(WTERMSIG(status))));
  report_corrupt(record_, problem());
}

FrameSource::Read ConvertedLogFrameSource::next_frame(can::CanFrame* frame,
                                                      std::int64_t* position) {
  can::CandumpRecord record;
  while (have_line_ || next_line()) {
    have_line_ = false;
    ++mutable_stats().lines;
    if (starts_with(line_, kErrorPrefix)) {
      char* end = nullptr;
      record_ = std::strtoll(line_.c_str() + kErrorPrefix.size(), &end, 10);
      report_corrupt(record_, std::string(end != nullptr && *end == ' ' ? end + 1 : ""));
      continue;
    }
    if (starts_with(line_, kFatalPrefix)) {
      report_corrupt(record_, line_.substr(kFatalPrefix.size()));
      continue;
    }
    ++record_;
    if (can::parse_candump_line(line_, &record, &why_) != can::CandumpLine::kFrame) {
      report_corrupt(record_, "converter output: " + why_);
      continue;
    }
    interface_.assign(record.interface.data(), record.interface.size());
    *position = record_;
    *frame = record.frame;
    return Read::kFrame;
  }
  finish();
  return Read::kEnd;
}

}  // namespace vmass::runtime
