// libFuzzer target: the candump -l line parser. The input is read as a log by CandumpReader
// (every line, bounded line length) and, whole, as one line by parse_candump_line. Every frame
// parsed is formatted back (format_candump_line) and parsed again: the round trip must give
// the same frame, or the writer and the reader disagree.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <string_view>

#include "vmass/can/candump.hpp"

namespace {

bool same_frame(const vmass::can::CanFrame& a, const vmass::can::CanFrame& b) {
  return a.time_us == b.time_us && a.id == b.id && a.flags == b.flags && a.len == b.len &&
         std::memcmp(a.data, b.data, a.len) == 0;
}

void round_trip(const vmass::can::CandumpRecord& record) {
  const std::string line = vmass::can::format_candump_line(record.frame, record.interface);
  vmass::can::CandumpRecord again;
  std::string error;
  const std::string_view body(line.data(), line.empty() ? 0 : line.size() - 1);  // no '\n'
  if (vmass::can::parse_candump_line(body, &again, &error) != vmass::can::CandumpLine::kFrame ||
      !same_frame(record.frame, again.frame) || again.interface != record.interface) {
    __builtin_trap();  // the writer wrote what the reader does not read back
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  vmass::can::CandumpRecord record;
  std::string error;
  if (vmass::can::parse_candump_line(text, &record, &error) == vmass::can::CandumpLine::kFrame) {
    round_trip(record);
  }
  std::istringstream in(text);
  vmass::can::CandumpReader reader(in, "fuzz.log");
  while (reader.next(&record)) round_trip(record);
  return 0;
}
