#include "vmass/runtime/log_frame_source.hpp"

#include <fstream>

#include "vmass/io/regular_file.hpp"
#include "vmass/runtime/blf_log_frame_source.hpp"
#include "vmass/runtime/converted_log_frame_source.hpp"
#include "vmass/runtime/text_log_frame_source.hpp"

namespace vmass::runtime {
namespace {

/// Why a file of this format is not a CAN log vmass reads ("" when it is one).
std::string refusal(can::LogFormat format) {
  switch (format) {
    case can::LogFormat::kLcmLog:
      return "an LCM log (lcm-logger), not CAN frames: plot it with vmass-plot --estimates";
    case can::LogFormat::kMdf3:
      return "MDF version 3 has no CAN bus logging: convert it to MDF4";
    case can::LogFormat::kUnknown:
      return "not a CAN log vmass reads (candump -l, candump screen output, Vector ASC, "
             "PEAK TRC, Vector BLF, ASAM MDF4 bus logging)";
    default:
      return "";
  }
}

}  // namespace

FrameSource::Read LogFrameSource::read(can::CanFrame* frame, int /*timeout_ms*/) {
  std::int64_t position = 0;
  Read got = Read::kEnd;
  while ((got = next_frame(frame, &position)) == Read::kFrame) {
    if (!selection_ || selection_->take(interface_name())) {
      count_frame(*frame, position);
      break;
    }
  }
  return got;
}

void LogFrameSource::count_frame(const can::CanFrame& frame, std::int64_t position) {
  position_ = position;
  ++stats_.frames;
  if (frame.fd()) ++stats_.fd_frames;
  if (frame.remote()) ++stats_.remote_frames;
  if (frame.error()) ++stats_.error_frames;
}

void LogFrameSource::report_corrupt(std::int64_t position, const std::string& why) {
  if (stats_.corrupt == 0) first_corrupt_ = {position, why};
  ++stats_.corrupt;
  const std::string where = can::is_binary_format(format_) ? ":record " : ":";
  if (callback_) callback_({position, path_ + where + std::to_string(position) + ": " + why});
}

std::string LogFrameSource::no_frames_reason() const {
  if (stats_.frames > 0) return "";
  // Frames on other interfaces: the name is what is wrong, not the lines.
  if (selection_ && (selection_->skipped() > 0 || stats_.corrupt == 0)) {
    return path_ + ": " + selection_->none_taken_reason();
  }
  if (stats_.corrupt == 0) return "";
  const std::string unit(this->unit());
  return path_ + ": no frames: " + std::to_string(stats_.corrupt) + " of " +
         std::to_string(stats_.lines) + " " + unit + "s could not be read; the first, " + unit +
         " " + std::to_string(first_corrupt_.line) + ": " + first_corrupt_.message;
}

std::unique_ptr<LogFrameSource> open_log_frame_source(const std::string& path, std::string* error,
                                                      bool require_time) {
  // A regular file or a pipe (candump -l | vmassd --replay /dev/stdin); never a directory or a
  // device such as /dev/zero.
  std::unique_ptr<std::ifstream> file = io::open_input_stream(path, "log", error);
  if (!file) return nullptr;
  // A pipe cannot be read ahead and rewound: its format is found from its first line.
  if (!io::check_input_file(path, false).empty()) {
    return TextLogFrameSource::from_stream(std::move(file), path, require_time, error);
  }
  std::string head(can::kLogFormatProbeBytes, '\0');
  file->read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(file->gcount()));
  const can::LogFormat format = can::detect_log_format(head);
  if (const std::string why = refusal(format); !why.empty()) {
    if (error) *error = path + ": " + why;
    return nullptr;
  }
  if (can::is_converted_format(format)) return ConvertedLogFrameSource::open(path, format, error);
  file->clear();
  file->seekg(0);
  if (format == can::LogFormat::kBlf)
    return std::make_unique<BlfLogFrameSource>(std::move(file), path);
  return std::make_unique<TextLogFrameSource>(std::move(file), path, format,
                                              can::make_log_line_parser(format, require_time));
}

}  // namespace vmass::runtime
