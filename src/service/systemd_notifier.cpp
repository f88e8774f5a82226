#include "vmass/service/systemd_notifier.hpp"

#include <systemd/sd-daemon.h>

#include <cstdlib>

namespace vmass::service {

SystemdNotifier::SystemdNotifier() {
  const char* socket = std::getenv("NOTIFY_SOCKET");
  enabled_ = socket != nullptr && socket[0] != '\0';
  std::uint64_t usec = 0;
  // unset_environment = 0: children (none) would inherit; keeps the variables for inspection.
  if (sd_watchdog_enabled(0, &usec) > 0) watchdog_usec_ = usec;
}

bool SystemdNotifier::notify(const std::string& state) {
  if (!enabled_) return false;
  const int r = sd_notify(0, state.c_str());
  if (r > 0) ++sent_;
  return r > 0;
}

bool SystemdNotifier::ready() { return notify("READY=1"); }
bool SystemdNotifier::stopping() { return notify("STOPPING=1"); }

bool SystemdNotifier::watchdog() {
  const bool ok = notify("WATCHDOG=1");
  if (ok) watchdog_ever_sent_ = true;
  return ok;
}

bool SystemdNotifier::status(const std::string& text) {
  std::string line = text;
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  if (line == last_status_) return false;
  last_status_ = line;
  return notify("STATUS=" + line);
}

bool SystemdNotifier::watchdog_due(std::uint64_t now_usec) const {
  if (!enabled_ || watchdog_usec_ == 0) return false;
  return !watchdog_ever_sent_ || now_usec - last_watchdog_usec_ >= watchdog_ping_interval_usec();
}

}  // namespace vmass::service
