// Number formatting benchmarks (Google Benchmark), per item:
//   csv/estimate_row        EstimateCsvWriter::format_row of a tick's estimate (9 numbers)
//   format/printf_fixed     snprintf("%.3f") of a mass: what the estimate CSV used before
//   format/to_chars_fixed   std::to_chars(fixed, 3) alone (libstdc++: Ryu printf)
//   format/write_fixed      write_fixed(3) (vmass/csv/fixed_decimal.hpp), what the CSV uses
// on masses drawn from [-5000, 5000] kg (seeded). CPU time.
#pragma once

namespace vmass::bench {

void register_format_benchmarks();

}  // namespace vmass::bench
