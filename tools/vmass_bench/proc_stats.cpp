#include "proc_stats.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace vmass::bench {

std::map<std::string, ThreadCpu> read_thread_cpu(pid_t pid) {
  std::map<std::string, ThreadCpu> out;
  const std::filesystem::path tasks = "/proc/" + std::to_string(pid) + "/task";
  std::error_code ec;
  for (const auto& task : std::filesystem::directory_iterator(tasks, ec)) {
    std::string name;
    std::ifstream(task.path() / "comm") >> name;
    std::uint64_t run_ns = 0, wait_ns = 0, slices = 0;
    std::ifstream(task.path() / "schedstat") >> run_ns >> wait_ns >> slices;
    if (name.empty()) continue;  // the thread ended meanwhile
    ThreadCpu& t = out[name];
    t.run_ns += run_ns;
    t.slices += slices;
  }
  return out;
}

Memory read_memory(pid_t pid) {
  Memory m;
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string key;
    long kb = 0;
    fields >> key >> kb;
    if (key == "VmRSS:") m.rss_kb = kb;
    if (key == "VmHWM:") m.hwm_kb = kb;
  }
  return m;
}

double read_load_average() {
  double load = 0.0;
  std::ifstream("/proc/loadavg") >> load;
  return load;
}

}  // namespace vmass::bench
