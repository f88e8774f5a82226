// excerpt(): user text as it may appear in a message. Files from many hands carry 50 MB tokens
// and binary bytes; a message quotes at most max_bytes of them, control bytes and bytes that are
// not UTF-8 as \xNN, and says how long the whole was:
//     excerpt("VehicleSpeed")            -> VehicleSpeed
//     excerpt(std::string(5e7, 'A'))     -> AAAA...AAAA... (50000000 bytes)
//
// Thread-safety: reentrant.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace vmass::io {

constexpr std::size_t kExcerptBytes = 64;

std::string excerpt(std::string_view text, std::size_t max_bytes = kExcerptBytes);

}  // namespace vmass::io
