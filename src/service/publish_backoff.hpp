// PublishBackoff: what the publisher thread does while LCM publishing fails (a tcpq:// server
// that is down, a network without a multicast route): it backs off, so that neither LCM's own
// reconnect messages nor ours flood the journal, and counts every message not published.
//
//   try_now(now)        false while backing off: the message is not sent (counted as failed)
//   record(ok, now)     after each attempt; consecutive failures double the pause, from 10 ms
//                       up to 5 s; a success ends it
//   log lines           the first failure at once, then at most one line every 10 s while it
//                       lasts (how many failed meanwhile), and one when publishing recovers
//
// Private to vmass_service. Not thread-safe: the publisher thread owns it.
#pragma once

#include <cstdint>
#include <string>

namespace vmass::service::daemon {

class PublishBackoff {
 public:
  static constexpr std::int64_t kFirstPauseNs = 10'000'000;
  static constexpr std::int64_t kMaxPauseNs = 5'000'000'000;
  static constexpr std::int64_t kLogEveryNs = 10'000'000'000;

  explicit PublishBackoff(std::string url) : url_(std::move(url)) {}

  bool try_now(std::int64_t now_ns);
  void record(bool ok, std::int64_t now_ns);

  std::int64_t failures() const { return failures_; }  ///< failed or skipped, since start
  std::int64_t published() const { return published_; }

 private:
  std::string url_;
  std::int64_t failures_ = 0;
  std::int64_t published_ = 0;
  int consecutive_ = 0;
  std::int64_t resume_at_ns_ = 0;
  std::int64_t next_log_ns_ = 0;
  std::int64_t failures_at_log_ = 0;
  std::int64_t failures_at_start_ = 0;  ///< when the current run of failures began
};

}  // namespace vmass::service::daemon
