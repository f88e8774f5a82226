#include "vmass/scoring/verdict_tally.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>

namespace vmass::scoring {

std::vector<std::pair<PairVerdict, long>> VerdictTally::refusals(Block block) const {
  const Counts& c = counts(block);
  std::vector<std::pair<PairVerdict, long>> out;
  for (std::size_t v = 0; v < kVerdictCount; ++v) {
    const auto verdict = static_cast<PairVerdict>(v);
    if (verdict != PairVerdict::kAccepted && c[v] > 0) out.emplace_back(verdict, c[v]);
  }
  // Most frequent first; a tie keeps the verdicts' order, so that the text is deterministic.
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  return out;
}

std::string VerdictTally::describe_refusals(Block block, std::size_t top) const {
  const Counts& c = counts(block);
  const long ticks = std::accumulate(c.begin(), c.end(), 0L);
  if (ticks == 0) return "";
  std::string out;
  const auto refused = refusals(block);
  for (std::size_t i = 0; i < refused.size() && i < top; ++i) {
    char share[32];
    std::snprintf(share, sizeof share, " %.1f %%",
                  100.0 * static_cast<double>(refused[i].second) / static_cast<double>(ticks));
    out += (i > 0 ? ", " : "") + std::string(verdict_name(refused[i].first)) + share;
  }
  return out;
}

}  // namespace vmass::scoring
