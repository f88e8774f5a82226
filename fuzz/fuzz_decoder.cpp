// libFuzzer target: the frame decoder with real DBC files (the demo vehicle's, and two of
// tests/data/dbc with multiplexing and CAN FD). The input is a stream of frames, each
//   flags (1 byte: FrameFlag bits) | id (4 bytes, little-endian) | len (1 byte) | data
// with id masked to 11/29 bits and len to at most 64 (and to what is left of the input).
// Every frame is decoded by each decoder's entry points: decode, decode_into, signal_value,
// SignalSelection, and the decoded values are encoded back with encode().
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "vmass/can/decoder.hpp"

#ifndef VMASS_SOURCE_DIR
#error "VMASS_SOURCE_DIR: the source tree, for its DBC files (set by fuzz/CMakeLists.txt)"
#endif

namespace {

struct Loaded {
  vmass::can::Decoder decoder;
  std::unique_ptr<vmass::can::SignalSelection> selection;
};

std::vector<Loaded>* g_decoders = nullptr;

Loaded load(const std::string& file) {
  const std::string path = std::string(VMASS_SOURCE_DIR) + "/" + file;
  vmass::can::DbcParseResult parsed = vmass::can::load_dbc_file(path);
  std::string error;
  auto decoder = vmass::can::Decoder::compile(std::move(parsed.database), &error);
  if (!parsed.ok() || !decoder) {
    std::fprintf(stderr, "fuzz_decoder: %s: cannot load: %s\n", path.c_str(), error.c_str());
    std::abort();
  }
  return Loaded{std::move(*decoder), nullptr};
}

void decode_all(const Loaded& l, const vmass::can::CanFrame& frame, std::vector<double>* values,
                std::vector<std::uint8_t>* present) {
  const vmass::can::Decoder& d = l.decoder;
  double sum = 0.0;
  int m = -1;
  d.decode(
      frame, [&](int, double v) { sum += v; }, &m);
  if (d.decode_into(frame, &m, values->data(), present->data()) != vmass::can::DecodeStatus::kOk) {
    return;
  }
  const int signals =
      static_cast<int>(d.database().messages[static_cast<std::size_t>(m)].signals.size());
  for (int i = 0; i < signals; ++i) {
    double v = 0.0;
    if (d.signal_value(frame, vmass::can::SignalRef{m, i}, &v)) sum += v;
  }
  l.selection->decode(frame, [&](int, double v) { sum += v; });
  vmass::can::CanFrame encoded;
  d.encode(m, values->data(), &encoded);
  volatile double sink = sum;  // keeps the decoding from being optimised away
  (void)sink;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  g_decoders = new std::vector<Loaded>();
  for (const char* file :
       {"config/demo_vehicle.dbc", "tests/data/dbc/gm_global_a_high_voltage_management.dbc",
        "tests/data/dbc/tesla_model3_vehicle.dbc"}) {
    g_decoders->push_back(load(file));
  }
  for (Loaded& l : *g_decoders) {  // select every signal of every message
    l.selection = std::make_unique<vmass::can::SignalSelection>(l.decoder);
    for (int m = 0; m < l.decoder.message_count(); ++m) {
      const auto& msg = l.decoder.database().messages[static_cast<std::size_t>(m)];
      for (int s = 0; s < static_cast<int>(msg.signals.size()); ++s) {
        l.selection->add(vmass::can::SignalRef{m, s});
      }
    }
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::size_t max_signals = 1;
  for (const Loaded& l : *g_decoders) {
    max_signals =
        std::max(max_signals, static_cast<std::size_t>(l.decoder.max_signals_per_message()));
  }
  std::vector<double> values(max_signals);
  std::vector<std::uint8_t> present(max_signals);
  std::size_t at = 0;
  while (size - at >= 6) {
    vmass::can::CanFrame frame;
    frame.flags = data[at];
    std::uint32_t id = 0;
    std::memcpy(&id, data + at + 1, sizeof id);
    frame.id = id & (frame.extended() ? vmass::can::kEffMask : vmass::can::kSffMask);
    // A frame holds at most 8 bytes, 64 when it is CAN FD (CanFrame's invariant).
    const int max_len = frame.fd() ? vmass::can::kFdMaxLen : vmass::can::kClassicMaxLen;
    std::size_t len = std::min<std::size_t>(data[at + 5], static_cast<std::size_t>(max_len));
    at += 6;
    len = std::min(len, size - at);
    frame.len = static_cast<std::uint8_t>(len);
    std::memcpy(frame.data, data + at, len);
    at += len;
    for (const Loaded& l : *g_decoders) decode_all(l, frame, &values, &present);
  }
  return 0;
}
