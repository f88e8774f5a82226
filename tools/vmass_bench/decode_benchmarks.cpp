#include "decode_benchmarks.hpp"

#include <benchmark/benchmark.h>

#include <string_view>

#include "vmass/can/candump.hpp"
#include "vmass/runtime/can_input_source.hpp"
#include "vmass/runtime/candump_frame_source.hpp"

namespace vmass::bench {
namespace {

void decode_every_signal(benchmark::State& state, const DecodeBenchData& data) {
  // The consumer stores each value by signal index, as vmass-can decode's formatter reads them.
  std::vector<double> values(static_cast<std::size_t>(data.decoder->max_signals_per_message()));
  double* out = values.data();
  const std::vector<can::CanFrame>& frames = data.frames.frames;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's loop
    for (const can::CanFrame& f : frames) {
      data.decoder->decode(f, [out](int i, double v) { out[i] = v; });
    }
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(frames.size()));
}

void apply_as_the_daemon(benchmark::State& state, const DecodeBenchData& data,
                         const std::vector<can::CanFrame>& frames) {
  runtime::CanInputSource source(runtime::CandumpFrameSource::from_text("", "bench"), data.decoder,
                                 data.mapping);
  std::vector<runtime::InputRecord> records(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    records[i].time_us = frames[i].time_us;
    records[i].frame = frames[i];
  }
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's loop
    for (const runtime::InputRecord& r : records) source.apply(r);
    benchmark::ClobberMemory();
  }
  benchmark::DoNotOptimize(source.table().counters().decoded);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(frames.size()));
}

void parse_lines(benchmark::State& state, const DecodeBenchData& data) {
  const std::string_view text = data.frames.candump_text;
  can::CandumpRecord record;
  std::int64_t lines = 0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's loop
    for (std::size_t begin = 0; begin < text.size();) {
      std::size_t end = text.find('\n', begin);
      if (end == std::string_view::npos) end = text.size();
      can::parse_candump_line(text.substr(begin, end - begin), &record);
      benchmark::DoNotOptimize(record.frame.id);
      begin = end + 1;
      ++lines;
    }
  }
  state.SetItemsProcessed(lines);
}

void read_log(benchmark::State& state, const DecodeBenchData& data) {
  can::CanFrame frame;
  std::int64_t frames = 0;
  for (auto _ : state) {  // NOLINT(clang-analyzer-deadcode.DeadStores): benchmark's loop
    state.PauseTiming();
    auto source = runtime::CandumpFrameSource::from_text(data.frames.candump_text, "bench");
    state.ResumeTiming();
    while (source->read(&frame, 0) == runtime::FrameSource::Read::kFrame) ++frames;
    benchmark::DoNotOptimize(frame.id);
  }
  state.SetItemsProcessed(frames);
}

}  // namespace

void register_decode_benchmarks(const DecodeBenchData& data) {
  const DecodeBenchData* d = &data;
  benchmark::RegisterBenchmark("decode/vmass-can",
                               [d](benchmark::State& s) { decode_every_signal(s, *d); });
  benchmark::RegisterBenchmark(
      "decode/daemon", [d](benchmark::State& s) { apply_as_the_daemon(s, *d, d->frames.frames); });
  benchmark::RegisterBenchmark("decode/daemon_mapped", [d](benchmark::State& s) {
    apply_as_the_daemon(s, *d, d->mapped_frames);
  });
  benchmark::RegisterBenchmark("candump/parse_line",
                               [d](benchmark::State& s) { parse_lines(s, *d); });
  benchmark::RegisterBenchmark("candump/read", [d](benchmark::State& s) { read_log(s, *d); });
}

}  // namespace vmass::bench
