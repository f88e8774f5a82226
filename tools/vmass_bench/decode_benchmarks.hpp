// Decoding benchmarks (Google Benchmark), per frame or line:
//   decode/vmass-can       Decoder::decode of every signal (what `vmass-can decode` runs)
//   decode/daemon          CanInputSource::apply (SignalTable::on_frame: the mapped signals
//                          only), the daemon's own path, on the same frames: most of them of
//                          messages the mapping does not use, as on a real bus
//   decode/daemon_mapped   the same on the frames of mapped messages only (the worst case)
//   candump/parse_line     parse_candump_line on the frames' candump -l lines
//   candump/read           CandumpFrameSource reading the same log from memory (line splitting,
//                          the stream, the parse)
// Times are CPU time, so that other load on a shared machine skews them less.
#pragma once

#include <memory>
#include <vector>

#include "bench_frames.hpp"
#include "vmass/can/decoder.hpp"
#include "vmass/signals/signal_mapping.hpp"

namespace vmass::bench {

struct DecodeBenchData {
  std::shared_ptr<const can::Decoder> decoder;
  signals::SignalMapping mapping;
  BenchFrames frames;
  std::vector<can::CanFrame> mapped_frames;  ///< of messages the mapping uses
};

/// Registers the benchmarks above over `data`, which must outlive them.
void register_decode_benchmarks(const DecodeBenchData& data);

}  // namespace vmass::bench
