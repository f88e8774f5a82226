#include "publish_backoff.hpp"

#include <algorithm>

#include <spdlog/spdlog.h>

namespace vmass::service::daemon {

bool PublishBackoff::try_now(std::int64_t now_ns) {
  if (consecutive_ == 0 || now_ns >= resume_at_ns_) return true;
  ++failures_;  // not sent: as good as failed
  return false;
}

void PublishBackoff::record(bool ok, std::int64_t now_ns) {
  if (ok) {
    ++published_;
    if (consecutive_ > 0) {
      spdlog::info("LCM publishing on {} recovered after {} messages not published", url_,
                   failures_ - failures_at_start_);
    }
    consecutive_ = 0;
    return;
  }
  ++failures_;
  if (consecutive_ == 0) {
    failures_at_start_ = failures_ - 1;
    if (now_ns >= next_log_ns_) {
      spdlog::warn("LCM publish on {} failed; retrying with backoff (logged every 10 s at most)",
                   url_);
      next_log_ns_ = now_ns + kLogEveryNs;
      failures_at_log_ = failures_;
    }
  } else if (now_ns >= next_log_ns_) {
    spdlog::warn("LCM publish on {} still failing: {} messages not published in the last {:.0f} s",
                 url_, failures_ - failures_at_log_, kLogEveryNs * 1e-9);
    next_log_ns_ = now_ns + kLogEveryNs;
    failures_at_log_ = failures_;
  }
  const int doublings = std::min(consecutive_, 30);
  const std::int64_t pause = std::min(kMaxPauseNs, kFirstPauseNs << doublings);
  ++consecutive_;
  resume_at_ns_ = now_ns + pause;
}

}  // namespace vmass::service::daemon
