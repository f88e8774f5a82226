#include "vmass/calibrate/ballast_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

namespace vmass::calibrate {
namespace {

std::string kg(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g kg", v);
  return buf;
}

std::string mm(double v_m) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g mm", v_m * 1e3);
  return buf;
}

}  // namespace

std::vector<BallastStep> group_samples(const std::vector<BallastSample>& samples) {
  // Two-pass mean and spread per mass. NaN masses cannot be map keys: each one becomes its own
  // step so that check_steps() reports it.
  std::map<double, std::vector<double>> by_mass;
  std::vector<BallastStep> out;
  for (const BallastSample& s : samples) {
    if (std::isnan(s.added_mass_kg)) {
      BallastStep step;
      step.added_mass_kg = s.added_mass_kg;
      step.deflection_m = s.deflection_m;
      step.sample_count = 1;
      out.push_back(step);
      continue;
    }
    by_mass[s.added_mass_kg].push_back(s.deflection_m);
  }
  for (const auto& [mass, zs] : by_mass) {
    BallastStep step;
    step.added_mass_kg = mass;
    step.sample_count = static_cast<int>(zs.size());
    double sum = 0.0;
    for (double z : zs) sum += z;
    step.deflection_m = sum / static_cast<double>(zs.size());
    if (zs.size() > 1) {
      double ss = 0.0;
      for (double z : zs) ss += (z - step.deflection_m) * (z - step.deflection_m);
      step.deflection_std_m = std::sqrt(ss / static_cast<double>(zs.size() - 1));
    }
    out.push_back(step);
  }
  std::stable_sort(out.begin(), out.end(), [](const BallastStep& a, const BallastStep& b) {
    return a.added_mass_kg < b.added_mass_kg;
  });
  return out;
}

std::string check_steps(const std::vector<BallastStep>& steps) {
  for (const BallastStep& s : steps) {
    if (!std::isfinite(s.added_mass_kg)) {
      return "an added mass is " + std::string(std::isnan(s.added_mass_kg) ? "NaN" : "infinite");
    }
    if (!std::isfinite(s.deflection_m)) {
      return "the deflection at added mass " + kg(s.added_mass_kg) + " is " +
             (std::isnan(s.deflection_m) ? "NaN" : "infinite");
    }
  }
  std::vector<BallastStep> sorted = steps;
  std::stable_sort(sorted.begin(), sorted.end(), [](const BallastStep& a, const BallastStep& b) {
    return a.added_mass_kg < b.added_mass_kg;
  });
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    if (sorted[i].added_mass_kg == sorted[i - 1].added_mass_kg) {
      return "two steps have the same added mass " + kg(sorted[i].added_mass_kg) +
             " (give each load once, or its samples as rows of one step)";
    }
  }
  if (sorted.size() < 3) {
    return "need at least three distinct loads to fit a stiffness and its uncertainty, got " +
           std::to_string(sorted.size());
  }
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    if (!(sorted[i].deflection_m > sorted[i - 1].deflection_m)) {
      return "the deflection does not increase with the load: " + kg(sorted[i - 1].added_mass_kg) +
             " gives " + mm(sorted[i - 1].deflection_m) + " but " + kg(sorted[i].added_mass_kg) +
             " gives " + mm(sorted[i].deflection_m) +
             " (wrong sign or column, a sensor fault, or a load that was not added)";
    }
  }
  return "";
}

}  // namespace vmass::calibrate
