#include "daemon_process.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

namespace vmass::bench {

pid_t start_command(const std::vector<std::string>& command, const std::string& log_path, int fd,
                    int as_fd) {
  const pid_t pid = fork();
  if (pid != 0) return pid;
  const int log = ::open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (log < 0 || dup2(log, STDOUT_FILENO) < 0 || dup2(log, STDERR_FILENO) < 0) _exit(127);
  // dup2 clears close-on-exec on the copy, but does nothing when fd is as_fd already.
  if ((fd == as_fd ? fcntl(as_fd, F_SETFD, 0) : dup2(fd, as_fd)) < 0) _exit(127);
  std::vector<char*> argv;
  argv.reserve(command.size() + 1);
  for (const std::string& a : command) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  execvp(argv[0], argv.data());
  _exit(127);
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string stopped_line(const std::string& log) {
  const std::size_t stopped = log.rfind("stopped:");
  if (stopped == std::string::npos) return "";
  return log.substr(stopped, log.find('\n', stopped) - stopped);
}

}  // namespace vmass::bench
