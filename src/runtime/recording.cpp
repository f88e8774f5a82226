#include "vmass/runtime/recording.hpp"

#include "vmass/signals/signal_mapping.hpp"

namespace vmass::runtime {

LogRecording open_log_recording(const std::string& path, const Config& config) {
  LogRecording out;
  signals::CanInputsLoad can = signals::load_can_inputs(config);
  if (!can.ok()) {
    out.error = can.error;
    return out;
  }
  out.warnings = can.inputs->warnings;
  std::unique_ptr<LogFrameSource> frames = open_log_frame_source(path, &out.error);
  if (!frames) return out;
  out.log = frames.get();
  out.source =
      std::make_unique<CanInputSource>(std::move(frames), can.inputs->decoder, can.inputs->mapping);
  out.can = std::move(can.inputs);
  return out;
}

}  // namespace vmass::runtime
