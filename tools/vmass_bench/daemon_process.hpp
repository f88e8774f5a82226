// The daemon under test, as vmass-bench-daemon and vmass-soak run it: a command started with
// one descriptor handed to it (the bus) and its output in a log file, and that log read back
// for the daemon's final "stopped:" line.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace vmass::bench {

/// Forks and runs `command` (argv; found on PATH) with `fd` as its descriptor `as_fd` (3 for a
/// --can-fd socket, 0 for a --replay /dev/stdin pipe) and its standard output and error into
/// `log_path` (truncated). Returns the child's pid, or -1 when fork failed.
pid_t start_command(const std::vector<std::string>& command, const std::string& log_path, int fd,
                    int as_fd);

/// The whole file ("" when it cannot be read).
std::string read_text(const std::string& path);

/// The daemon's final log line, from "stopped:" to its end; "" when the log has none.
std::string stopped_line(const std::string& log);

}  // namespace vmass::bench
