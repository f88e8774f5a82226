#include "paper_roads.hpp"

#include <utility>

namespace vmass::sim {

PiecewiseLinear slope_percent(std::vector<PiecewiseLinear::Point> points) {
  for (auto& p : points) p.y = grade_from_percent(p.y);
  return PiecewiseLinear(std::move(points));
}

Road paper_exp1_road() {
  Road road;
  road.grade_rad = slope_percent({{0, 0},
                                  {30, 0},
                                  {80, 3},
                                  {200, 3},
                                  {300, -2},
                                  {380, -2},
                                  {520, 4},
                                  {650, 4},
                                  {750, 0},
                                  {880, -3},
                                  {1100, -3},
                                  {1200, 0},
                                  {1400, 2},
                                  {1600, 0}});
  return road;
}

Road paper_exp2_road() {
  Road road;
  road.grade_rad = slope_percent({{0, 0},
                                  {50, 0},
                                  {200, 1.5},
                                  {500, 0},
                                  {800, -1},
                                  {1100, 0},
                                  {1500, 1},
                                  {1900, 1},
                                  {2200, 0}});
  road.bank_rad = PiecewiseLinear({{0, 0}, {1200, 0}, {1250, 0.02}, {1450, 0.02}, {1500, 0}});
  return road;
}

}  // namespace vmass::sim
