// Counts heap allocations, so that a test can prove a hot path makes none: the test executable
// that links tests/common/allocation_counter.cpp replaces the global operator new with one that
// counts. AddressSanitizer and ThreadSanitizer bring their own operator new, so under them
// nothing is counted and counting_allocations() is false: skip the check then, never pass it
// on a count of zero.
#pragma once

namespace vmass::testing {

/// False under a sanitizer (nothing is counted).
bool counting_allocations();
/// operator new calls since the program started.
long allocations();

}  // namespace vmass::testing
