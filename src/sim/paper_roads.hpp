// The roads of the paper's two experiments, one definition each: the demo scenarios
// (scenario_registry.cpp) and the population's (population_scenarios.cpp) drive on them.
#pragma once

#include <vector>

#include "vmass/sim/road.hpp"

namespace vmass::sim {

/// A slope profile in percent over distance (m), as a grade in rad.
PiecewiseLinear slope_percent(std::vector<PiecewiseLinear::Point> points);

/// Experiment 1: straight, slopes of -3..+4 % over the first 1.2 km, then a +2 % hill for the
/// population's second urban cycle (the demo's single cycle ends near 1 km).
Road paper_exp1_road();

/// Experiment 2: slopes of -1..+1.5 %, and a 2 % bank from 1.2 to 1.5 km.
Road paper_exp2_road();

}  // namespace vmass::sim
