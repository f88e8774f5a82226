// libFuzzer target: the Vector BLF reader (runtime::BlfReader, zlib). The input is read as a
// BLF file to its end. Whatever it holds: every frame is a CAN frame vmass can carry (an id
// within its width, a classic length up to 8, a CAN FD length of the DLC table), every damage
// is reported with its place, the records are counted one by one and bounded by the input's
// size, and the reader's buffers stay within its limits (a size in the file is never
// allocated). Seeds: python-can's BLFWriter files and hand-laid ones (fuzz/corpus/fuzz_blf).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "vmass/can/can_frame.hpp"
#include "vmass/runtime/blf_reader.hpp"

namespace {

bool is_can_frame(const vmass::can::CanFrame& f) {
  if (f.error()) return f.len <= vmass::can::kClassicMaxLen;
  if (f.id > (f.extended() ? vmass::can::kEffMask : vmass::can::kSffMask)) return false;
  if (f.fd()) return vmass::can::is_valid_fd_length(f.len) && !f.remote();
  return f.len <= vmass::can::kClassicMaxLen;
}

bool names_a_place(const std::string& why) {
  return why.find("file offset") != std::string::npos ||
         why.find("the file ends at byte") != std::string::npos ||
         why.find("the file has") != std::string::npos ||
         why.find("file header") != std::string::npos;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  vmass::runtime::BlfReader::Limits limits;
  limits.max_inflated_bytes = 1u << 20;  // a fuzzer's time is better spent than on bombs
  vmass::runtime::BlfReader reader(in, limits);
  vmass::runtime::BlfReader::Record record;
  std::string why;
  std::int64_t records = 0;
  const std::size_t most_bytes = (64u << 10) + limits.max_inflated_bytes + (256u << 10);
  for (;;) {
    const vmass::runtime::BlfReader::Next got = reader.next(&record, &why);
    if (reader.buffer_bytes() > most_bytes) __builtin_trap();
    if (got == vmass::runtime::BlfReader::Next::kEnd) break;
    if (reader.record_number() != ++records) __builtin_trap();
    if (records > static_cast<std::int64_t>(size) + 4) __builtin_trap();
    if (got == vmass::runtime::BlfReader::Next::kFrame && !is_can_frame(record.frame)) {
      __builtin_trap();
    }
    if (got == vmass::runtime::BlfReader::Next::kCorrupt && !names_a_place(why)) {
      __builtin_trap();
    }
  }
  return 0;
}
