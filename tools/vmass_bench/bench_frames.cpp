#include "bench_frames.hpp"

#include <algorithm>
#include <random>
#include <sstream>

#include "vmass/can/candump.hpp"

namespace vmass::bench {

std::vector<std::string> overlapping_messages(const can::DbcParseResult& parsed) {
  std::vector<std::string> names;
  for (const can::DbcDiagnostic& d : parsed.diagnostics) {
    const auto a = d.message.find(" of message ");
    const auto b = d.message.find(" overlaps ");
    if (a == std::string::npos || b == std::string::npos || b < a) continue;
    const std::string name = d.message.substr(a + 12, b - a - 12);
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  return names;
}

BenchFrames random_frames(const can::Decoder& decoder, const std::vector<std::string>& overlapping,
                          int count, std::uint64_t seed) {
  BenchFrames out;
  std::vector<int> usable;
  for (int m = 0; m < decoder.message_count(); ++m) {
    const can::Message& msg = decoder.database().messages[static_cast<std::size_t>(m)];
    const bool left_out =
        std::find(overlapping.begin(), overlapping.end(), msg.name) != overlapping.end();
    if (!left_out) usable.push_back(m);
  }
  out.messages_used = static_cast<int>(usable.size());
  out.messages_left_out = decoder.message_count() - out.messages_used;
  std::mt19937_64 rng(seed);
  std::ostringstream log;
  can::CandumpWriter writer(log);
  std::size_t signals = 0;
  for (int i = 0; i < count && !usable.empty(); ++i) {
    const can::Message& msg =
        decoder.database().messages[static_cast<std::size_t>(usable[rng() % usable.size()])];
    can::CanFrame f;
    f.time_us = 1700000000000000 + i;
    f.id = msg.id;
    f.flags =
        static_cast<std::uint8_t>((msg.extended ? can::kExtended : 0) | (msg.fd ? can::kFd : 0));
    f.len = static_cast<std::uint8_t>(msg.length);
    for (int b = 0; b < msg.length; ++b) f.data[b] = static_cast<std::uint8_t>(rng());
    out.frames.push_back(f);
    writer.write(f, "can0");
    decoder.decode(f, [&](int, double) { ++signals; });
  }
  out.candump_text = log.str();
  out.signals_per_frame = static_cast<double>(signals) / std::max(1, count);
  return out;
}

std::vector<can::CanFrame> frames_of(const can::Decoder& decoder,
                                     const std::vector<can::CanFrame>& frames,
                                     const std::vector<bool>& keep) {
  std::vector<can::CanFrame> out;
  for (const can::CanFrame& f : frames) {
    const int m = decoder.find_message(f.id, f.extended());
    if (m >= 0 && keep[static_cast<std::size_t>(m)]) out.push_back(f);
  }
  return out;
}

}  // namespace vmass::bench
