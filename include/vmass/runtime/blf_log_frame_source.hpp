// BlfLogFrameSource: the frames of a Vector BLF log, read natively (BlfReader, zlib): no
// converter, no Python. Each object of the log is a record (the unit "record" in reports):
// a frame, an object of another type (counted with the lines without a frame: stats().comments),
// or corrupt (counted, reported "path:record N: why" with the file offset, skipped), as the text
// formats report their lines. A truncated or damaged file gives its frames up to the damage
// (and after it, from the next intact object) and a located message; a read error ends the log
// with problem() "path: read error: why", never taken for the end of the file.
//
// Thread-safety: one reading thread.
#pragma once

#include <istream>
#include <memory>
#include <string>
#include <string_view>

#include "vmass/runtime/blf_reader.hpp"
#include "vmass/runtime/log_frame_source.hpp"

namespace vmass::runtime {

class BlfLogFrameSource final : public LogFrameSource {
 public:
  /// Reads `in` from its current position (the file's first byte).
  BlfLogFrameSource(std::unique_ptr<std::istream> in, const std::string& path);
  std::string_view interface_name() const override { return interface_; }
  /// The objects of type `type` skipped as carrying no frame.
  std::uint64_t objects_without_frame(std::uint32_t type) const {
    return reader_.objects_without_frame(type);
  }

 protected:
  Read next_frame(can::CanFrame* frame, std::int64_t* position) override;

 private:
  std::unique_ptr<std::istream> in_;
  BlfReader reader_;
  BlfReader::Record record_;
  std::string why_, interface_;
  int channel_ = -1;  ///< the channel interface_ names
};

}  // namespace vmass::runtime
