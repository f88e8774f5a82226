#include "vmass/core/load_change_odds.hpp"

#include <cmath>

#include "vmass/core/constants.hpp"

namespace vmass {

double load_change_probability(double difference_kg, double difference_std_kg, double span_kg,
                               double prior_probability) {
  const bool weighable = std::isfinite(difference_kg) && std::isfinite(difference_std_kg) &&
                         difference_std_kg > 0.0 && std::isfinite(span_kg) && span_kg > 0.0;
  if (!weighable) return prior_probability;
  const double z = difference_kg / difference_std_kg;
  // Both likelihoods times sqrt(2 pi) s, so that a tiny s cannot overflow the normal's density.
  const double same = (1.0 - prior_probability) * std::exp(-0.5 * z * z);
  const double changed = prior_probability * std::sqrt(2.0 * kPi) * difference_std_kg / span_kg;
  const double total = changed + same;
  return total > 0.0 ? changed / total : prior_probability;
}

}  // namespace vmass
