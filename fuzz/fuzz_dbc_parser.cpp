// libFuzzer target: the DBC parser (parse_dbc), tolerant and strict, then the decoder compiler
// and a decode of an all-ones frame of every message that compiled. Any input is allowed: the
// parser reports errors as diagnostics and never throws.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "vmass/can/decoder.hpp"

namespace {

void decode_each_message(const vmass::can::Decoder& decoder) {
  vmass::can::CanFrame frame;
  for (std::uint8_t& b : frame.data) b = 0xFF;
  double sum = 0.0;
  for (const vmass::can::Message& m : decoder.database().messages) {
    frame.id = m.id;
    frame.flags = static_cast<std::uint8_t>((m.extended ? vmass::can::kExtended : 0) |
                                            (m.fd ? vmass::can::kFd : 0));
    frame.len = static_cast<std::uint8_t>(m.length);
    decoder.decode(frame, [&](int, double v) { sum += v; });
  }
  volatile double sink = sum;  // keeps the decoding from being optimised away
  (void)sink;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  for (const bool strict : {false, true}) {
    vmass::can::DbcParseOptions options;
    options.strict = strict;
    vmass::can::DbcParseResult result = vmass::can::parse_dbc(text, "fuzz.dbc", options);
    for (const vmass::can::DbcDiagnostic& d : result.diagnostics) (void)d.to_string();
    if (strict) break;  // the strict parse only checks that strictness itself is safe
    std::string error;
    const auto decoder = vmass::can::Decoder::compile(std::move(result.database), &error);
    if (decoder) decode_each_message(*decoder);
  }
  return 0;
}
