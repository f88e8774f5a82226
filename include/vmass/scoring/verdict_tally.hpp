// VerdictTally: why each block took, or did not take, a pair at each tick of a run: the count
// of every verdict (extraction.hpp) per block. It answers "why no pair?" when a run ends at its
// prior (a cruise whose force never changes: small_delta_force; a car too slow: speed), which
// the status alone (`initialising (no_load_sensor)`) does not say.
//
// Not thread-safe; add() allocates nothing.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "vmass/core/extraction.hpp"
#include "vmass/core/regression_pair.hpp"
#include "vmass/core/supervisor.hpp"

namespace vmass::scoring {

constexpr std::size_t kVerdictCount = static_cast<std::size_t>(PairVerdict::kCount);

class VerdictTally {
 public:
  using Counts = std::array<long, kVerdictCount>;

  /// One tick's outcome of every block.
  void add(const std::array<PairEvent, kBlockCount>& events) {
    for (std::size_t b = 0; b < events.size(); ++b) {
      ++counts_[b][static_cast<std::size_t>(events[b].verdict)];
    }
  }

  const Counts& counts(Block block) const { return counts_[static_cast<std::size_t>(block)]; }

  /// The block's verdicts other than `accepted`, most frequent first, with their counts (the
  /// ones that happened).
  std::vector<std::pair<PairVerdict, long>> refusals(Block block) const;

  /// "small_delta_force 62.1 %, speed 30.0 %, warming_up 7.9 %": the `top` most frequent
  /// refusals as shares of the block's ticks; "" when it has no tick.
  std::string describe_refusals(Block block, std::size_t top = 3) const;

 private:
  std::array<Counts, kBlockCount> counts_{};
};

}  // namespace vmass::scoring
