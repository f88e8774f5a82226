// Whether a saved state is believable before the daemon restores it. A state file can carry a
// valid checksum and still say nonsense (written by another build, edited by hand, or by a
// fault upstream): a mass of -5000 kg restored would be published as "converged" for a whole
// drive. The checks, for the regressor the config uses:
//
//   every number finite; standard deviations, variances, the NIG shape and scale > 0;
//   covariance matrices symmetric (to 1e-9 relative) with a determinant >= 0;
//   masses (the prior, the regressor's mass) within
//       [0.5 M_empty, max(1.5 M_max, 5 M_empty)]   (M_max only when the config gives one);
//   counters >= 0 and accepted <= candidates <= ticks per block
//
// Returns "" for a believable state, else the first reason ("prior mass -5000 kg outside [750,
// 7500] kg"). Pure; reentrant.
#pragma once

#include <string>

#include "vmass/core/pipeline.hpp"

namespace vmass::service {

std::string implausible_state(const PipelineSnapshot& snapshot, const PipelineParams& params);

}  // namespace vmass::service
