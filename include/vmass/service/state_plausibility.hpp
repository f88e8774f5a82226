// Whether a saved state is believable before the daemon restores it. A state file can carry a
// valid checksum and still say nonsense (written by another build, edited by hand, or by a
// fault upstream): a mass of -5000 kg restored would be published as "converged" for a whole
// drive. The checks, for the regressor the config uses:
//
//   every number finite; standard deviations, variances, the NIG shape and scale > 0;
//   covariance matrices symmetric (to 1e-9 relative) with a determinant >= 0;
//   masses (the prior, the regressor's mass) in the band vmass publishes (plausible_band.hpp):
//       what it would refuse here it never publishes, and the daemon never saves;
//   the regressor's mass std at least 0.1 % of the mass / sqrt(pairs used): a degenerate
//       posterior would publish a zero-width interval that no pair moves again;
//   the reference standstill: its deflection reads (eq. 3) as a mass in the band, its spread
//       in [0, 1] m, its grade acceleration within +-g (or NaN: unknown);
//   counters >= 0 and accepted <= candidates <= ticks per block
//
// Returns "" for a believable state, else the first reason ("prior mass -5000 kg outside the
// plausible band [1350, 2500] kg"). Pure; reentrant.
#pragma once

#include <string>

#include "vmass/core/pipeline.hpp"

namespace vmass::service {

std::string implausible_state(const PipelineSnapshot& snapshot, const PipelineParams& params);

}  // namespace vmass::service
