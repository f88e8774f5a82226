#include "bus_feed.hpp"

#include <time.h>

#include <algorithm>
#include <cstring>
#include <fstream>

#include "vmass/can/candump.hpp"

namespace vmass::bench {
namespace {

std::int64_t mono_us() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000 + ts.tv_nsec / 1000;
}

void sleep_until_us(std::int64_t t_us) {
  const timespec ts{static_cast<time_t>(t_us / 1'000'000),
                    static_cast<long>((t_us % 1'000'000) * 1000)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) != 0) {
  }
}

can_frame to_socketcan(const can::CanFrame& f) {
  can_frame raw{};
  raw.can_id = f.id | (f.extended() ? CAN_EFF_FLAG : 0u);
  raw.len = std::min<std::uint8_t>(f.len, CAN_MAX_DLEN);
  std::memcpy(raw.data, f.data, raw.len);
  return raw;
}

}  // namespace

std::string read_log_frames(const std::string& path, std::vector<can::CanFrame>* frames) {
  std::ifstream in(path);
  if (!in) return path + ": cannot read";
  can::CandumpReader reader(in, path);
  can::CandumpRecord record;
  while (reader.next(&record)) {
    if (!record.frame.fd()) frames->push_back(record.frame);  // classic frames: can_frame
  }
  if (frames->empty()) return path + ": no classic frames";
  return "";
}

BusFeed::BusFeed(std::vector<can::CanFrame> log_frames, std::vector<std::uint32_t> filler_ids,
                 int filler_period_ms)
    : log_(std::move(log_frames)),
      filler_ids_(std::move(filler_ids)),
      filler_period_us_(std::int64_t{1000} * std::max(1, filler_period_ms)) {
  const std::int64_t t0 = log_.front().time_us;
  for (can::CanFrame& f : log_) f.time_us -= t0;
  log_span_us_ = std::max<std::int64_t>(1, log_.back().time_us + 1);
}

double BusFeed::filler_frames_per_s() const {
  return static_cast<double>(filler_ids_.size()) * 1e6 / static_cast<double>(filler_period_us_);
}

void BusFeed::send_due(int fd, std::int64_t now_us) {
  due_.clear();
  while (log_offset_us_ + log_[next_log_].time_us <= now_us) {
    due_.push_back(log_[next_log_]);
    ++stats_.log_frames;
    if (++next_log_ == log_.size()) {  // loop the drive
      next_log_ = 0;
      log_offset_us_ += log_span_us_;
    }
  }
  for (; next_filler_us_ <= now_us; next_filler_us_ += filler_period_us_) {
    for (const std::uint32_t id : filler_ids_) {
      can::CanFrame f;
      f.id = id;
      f.len = 8;
      f.data[0] = static_cast<std::uint8_t>(stats_.filler_frames++);
      due_.push_back(f);
    }
  }
  raw_.resize(due_.size());
  iov_.resize(due_.size());
  msgs_.resize(due_.size());
  for (std::size_t i = 0; i < due_.size(); ++i) {
    raw_[i] = to_socketcan(due_[i]);
    iov_[i] = {&raw_[i], sizeof(can_frame)};
    msgs_[i] = {};
    msgs_[i].msg_hdr.msg_iov = &iov_[i];
    msgs_[i].msg_hdr.msg_iovlen = 1;
  }
  const int sent =
      due_.empty() ? 0
                   : sendmmsg(fd, msgs_.data(), static_cast<unsigned>(msgs_.size()), MSG_DONTWAIT);
  stats_.dropped += due_.size() - static_cast<std::size_t>(std::max(0, sent));
}

void BusFeed::run(int fd, const std::atomic<bool>& stop) {
  const std::int64_t start = mono_us();
  next_filler_us_ = 0;
  std::int64_t t = 0;
  for (; !stop.load(std::memory_order_relaxed); t += 1000) {
    sleep_until_us(start + t);
    send_due(fd, t);
  }
  stats_.seconds = static_cast<double>(t) * 1e-6;
}

}  // namespace vmass::bench
