#include "vmass/runtime/candump_frame_source.hpp"

#include <cerrno>
#include <cstring>

namespace vmass::runtime {

CandumpFrameSource::CandumpFrameSource(const std::string& path)
    : path_(path), in_(path, std::ios::binary) {
  reader_ = std::make_unique<can::CandumpReader>(in_, path);
}

std::unique_ptr<CandumpFrameSource> CandumpFrameSource::open(const std::string& path,
                                                             std::string* error) {
  std::unique_ptr<CandumpFrameSource> s(new CandumpFrameSource(path));
  if (!s->in_) {
    if (error) *error = path + ": cannot open the log: " + std::strerror(errno);
    return nullptr;
  }
  return s;
}

FrameSource::Read CandumpFrameSource::read(can::CanFrame* frame, int /*timeout_ms*/) {
  can::CandumpRecord record;
  if (!reader_->next(&record)) return Read::kEnd;
  *frame = record.frame;
  return Read::kFrame;
}

}  // namespace vmass::runtime
