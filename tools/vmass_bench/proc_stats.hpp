// What /proc says about a running process: CPU time per thread (schedstat: nanoseconds on the
// CPU, and how many times it was scheduled in), resident memory now and at its peak, and the
// machine's load average. Read before and after a measured window, the difference is the
// process's cost over it. Linux only; not thread-safe.
#pragma once

#include <sys/types.h>

#include <cstdint>
#include <map>
#include <string>

namespace vmass::bench {

struct ThreadCpu {
  std::uint64_t run_ns = 0;  ///< time on a CPU
  std::uint64_t slices = 0;  ///< times scheduled in (wake-ups, preemptions)
};

/// Per thread name (several threads of one name are summed), from /proc/PID/task/*/.
std::map<std::string, ThreadCpu> read_thread_cpu(pid_t pid);

struct Memory {
  long rss_kb = 0;  ///< VmRSS
  long hwm_kb = 0;  ///< VmHWM (peak)
};
Memory read_memory(pid_t pid);

/// The 1-minute load average.
double read_load_average();

}  // namespace vmass::bench
