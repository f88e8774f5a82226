// MassPrior: what is believed about theta = [M, mu] before any dynamic event, normally from the
// static initialisation (eq. 3). Both regressors start from it and restart from it when the load
// changes.
#pragma once

namespace vmass {

struct MassPrior {
  double mass_kg = 0.0;
  double mass_std_kg = 0.0;  ///< > 0
  double mu_n = 0.0;
  double mu_std_n = 0.0;  ///< > 0
};

}  // namespace vmass
