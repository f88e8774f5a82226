#include "vmass/runtime/blf_log_frame_source.hpp"

namespace vmass::runtime {

BlfLogFrameSource::BlfLogFrameSource(std::unique_ptr<std::istream> in, const std::string& path)
    : LogFrameSource(path, can::LogFormat::kBlf), in_(std::move(in)), reader_(*in_) {}

FrameSource::Read BlfLogFrameSource::next_frame(can::CanFrame* frame, std::int64_t* position) {
  for (;;) {
    const BlfReader::Next got = reader_.next(&record_, &why_);
    if (got == BlfReader::Next::kEnd) break;
    ++mutable_stats().lines;
    switch (got) {
      case BlfReader::Next::kFrame:
        if (record_.channel != channel_) {
          channel_ = record_.channel;
          interface_ = blf_interface_name(record_.channel);
        }
        *position = reader_.record_number();
        *frame = record_.frame;
        return Read::kFrame;
      case BlfReader::Next::kNoFrame:
        ++mutable_stats().comments;
        break;
      case BlfReader::Next::kCorrupt:
        report_corrupt(reader_.record_number(), why_);
        break;
      case BlfReader::Next::kEnd:
        break;
    }
  }
  if (!reader_.read_error().empty() && problem().empty()) {
    set_problem(path() + ": read error: " + reader_.read_error());
  }
  return Read::kEnd;
}

}  // namespace vmass::runtime
