#include "vmass/runtime/candump_frame_source.hpp"

#include <fstream>
#include <sstream>

#include "vmass/io/regular_file.hpp"

namespace vmass::runtime {

CandumpFrameSource::CandumpFrameSource(std::unique_ptr<std::istream> in, const std::string& path)
    : path_(path), in_(std::move(in)) {
  reader_ = std::make_unique<can::CandumpReader>(*in_, path);
}

std::unique_ptr<CandumpFrameSource> CandumpFrameSource::open(const std::string& path,
                                                             std::string* error) {
  // A regular file or a pipe (candump -l | vmassd --replay /dev/stdin); never a directory or a
  // device such as /dev/zero.
  std::unique_ptr<std::ifstream> file = io::open_input_stream(path, "log", error);
  if (!file) return nullptr;
  return std::unique_ptr<CandumpFrameSource>(new CandumpFrameSource(std::move(file), path));
}

std::unique_ptr<CandumpFrameSource> CandumpFrameSource::from_text(std::string text,
                                                                  const std::string& name) {
  return std::unique_ptr<CandumpFrameSource>(
      new CandumpFrameSource(std::make_unique<std::istringstream>(std::move(text)), name));
}

FrameSource::Read CandumpFrameSource::read(can::CanFrame* frame, int /*timeout_ms*/) {
  can::CandumpRecord record;
  if (!reader_->next(&record)) return Read::kEnd;
  *frame = record.frame;
  return Read::kFrame;
}

}  // namespace vmass::runtime
