// SystemdNotifier: the daemon's side of systemd's notify protocol (sd_notify(3), libsystemd):
//   READY=1      once the config, the DBC, the input and LCM are up
//   STATUS=...   a one-line summary, sent when it changes (at most once per status_period)
//   WATCHDOG=1   keep-alive; send at no more than half of WATCHDOG_USEC, and only while the
//                estimator loop proves it ticks (the caller decides; see watchdog_due())
//   STOPPING=1   on shutdown
// Outside systemd (no $NOTIFY_SOCKET) every call is a cheap no-op that returns false.
//
// Thread-safety: call from one thread (the daemon's main thread). Allocates (message text).
#pragma once

#include <cstdint>
#include <string>

namespace vmass::service {

class SystemdNotifier {
 public:
  /// Reads $NOTIFY_SOCKET and $WATCHDOG_USEC/$WATCHDOG_PID (sd_watchdog_enabled).
  SystemdNotifier();

  /// A notify socket is configured.
  bool enabled() const { return enabled_; }
  /// The watchdog interval systemd expects (0: no watchdog).
  std::uint64_t watchdog_usec() const { return watchdog_usec_; }
  /// Interval at which to send WATCHDOG=1: half of watchdog_usec() (0: none).
  std::uint64_t watchdog_ping_interval_usec() const { return watchdog_usec_ / 2; }

  bool ready();
  bool stopping();
  bool watchdog();
  /// STATUS=text (newlines replaced by spaces); not resent when unchanged.
  bool status(const std::string& text);
  /// Sends a raw notify state string (e.g. "READY=1\nSTATUS=up").
  bool notify(const std::string& state);

  /// Whether a WATCHDOG=1 is due at monotonic time now_usec (the last one was sent at least
  /// watchdog_ping_interval_usec() ago).
  bool watchdog_due(std::uint64_t now_usec) const;
  /// Records that WATCHDOG=1 was sent at now_usec.
  void watchdog_sent(std::uint64_t now_usec) { last_watchdog_usec_ = now_usec; }

  std::uint64_t notifications_sent() const { return sent_; }

 private:
  bool enabled_ = false;
  std::uint64_t watchdog_usec_ = 0;
  std::uint64_t last_watchdog_usec_ = 0;
  bool watchdog_ever_sent_ = false;
  std::string last_status_;
  std::uint64_t sent_ = 0;
};

}  // namespace vmass::service
