// Opening a recording as an InputSource, the same way for every front end:
//
//   a CAN log          CanInputSource over a LogFrameSource (candump -l, Vector ASC or BLF, PEAK
//                      TRC, ASAM MDF4, candump screen output with times: the format found from
//                      the content), decoded with the config's `can:` section (can.dbc +
//                      can.inputs; docs/signal-mapping.md)
//   a samples CSV      SamplesCsvSource; an input older than its timeout is stale (default:
//                      5 ticks, a gap in the recording)
//
// Configuration time only (allocates); not thread-safe.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "vmass/config/config.hpp"
#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/log_frame_source.hpp"
#include "vmass/runtime/samples_csv_source.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmass::runtime {

struct LogRecording {
  std::unique_ptr<CanInputSource> source;  ///< null when the log or the mapping cannot be used
  LogFrameSource* log = nullptr;           ///< the source's frames (format, statistics, errors)
  std::vector<std::string> warnings;       ///< DBC deviations that were tolerated
  std::string error;                       ///< "file:line: key: message" when source is null
  std::optional<signals::CanInputs> can;   ///< the DBC and mapping it decodes with (to log them)
};

/// A CAN log of any format vmass reads (log_frame_source.hpp) through the config's mapping.
LogRecording open_log_recording(const std::string& path, const Config& config);

/// The default staleness of a samples CSV's inputs: 5 ticks.
inline double default_samples_timeout_s(double tick_rate_hz) { return 5.0 / tick_rate_hz; }

}  // namespace vmass::runtime
