// load_change_probability: how likely a long stop changed the load, from how far the drive
// since the stop (the load monitor's challenger) reads from the belief before it.
//
// Both are readings of the load. Had the load not changed, their difference d would be the two
// readings' error: normal, with both variances and the model errors they do not share. Had it
// changed, the new load could be anywhere between empty and full, so d is spread evenly over
// that span W (the caller's: the capacity, or the plausible band without a maximum). Bayes'
// rule, with p0 the probability that a long stop changed the load before the drive says
// anything:
//   P(changed | d) = (p0 / W) / (p0 / W + (1 - p0) N(d; 0, s^2))
// Used once the challenger has had the pairs it needs and still neither decides a change nor
// agrees with the belief: a part of a drive, in fewer gears and on other roads than the whole,
// differs from it by more than its statistics say (LoadChangeMonitor, Pipeline).
//
// Pure arithmetic.
#pragma once

namespace vmass {

/// P(changed | d) above. Without evidence it can weigh (a std or a span that is not positive
/// and finite, a d that is not finite) it returns the prior.
double load_change_probability(double difference_kg, double difference_std_kg, double span_kg,
                               double prior_probability);

}  // namespace vmass
