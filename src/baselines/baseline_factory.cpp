#include "vmass/baselines/baseline_factory.hpp"

#include "vmass/baselines/fathy2008_baseline.hpp"
#include "vmass/baselines/paper_baseline.hpp"
#include "vmass/baselines/paper_lp_baseline.hpp"
#include "vmass/baselines/vahidi2005_baseline.hpp"

namespace vmass::baselines {

std::vector<std::string> baseline_names() {
  return {"paper", "paper_lp", "vahidi2005", "fathy2008"};
}

std::unique_ptr<MassBaseline> make_baseline(std::string_view name, const NominalVehicle& vehicle,
                                            double tick_rate_hz) {
  if (name == "paper") return std::make_unique<PaperBaseline>(vehicle, tick_rate_hz);
  if (name == "paper_lp") return std::make_unique<PaperLpBaseline>(vehicle, tick_rate_hz);
  if (name == "vahidi2005") return std::make_unique<Vahidi2005Baseline>(vehicle, tick_rate_hz);
  if (name == "fathy2008") return std::make_unique<Fathy2008Baseline>(vehicle, tick_rate_hz);
  return nullptr;
}

}  // namespace vmass::baselines
