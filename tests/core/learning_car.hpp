// The car the learning tests drive (the learnt scale, the learnt gear masses): the synthetic
// test vehicle without a deflection sensor, the Bayes estimator on short batches and a 5 Hz
// low-pass, so that a two-minute drive gives a regression narrow enough to be evidence.
#pragma once

#include "synthetic_drive.hpp"
#include "vmass/core/pipeline.hpp"

namespace vmass::testing {

inline PipelineParams learning_car() {
  PipelineParams p;
  p.vehicle = test_vehicle();
  p.vehicle.max_mass_kg = 2200.0;
  p.suspension.has_sensor = false;
  p.estimator.type = RegressorType::kBayes;
  p.estimator.bayes.noise_std_guess_n = 50.0;
  p.estimator.bayes.batch_size = 50;
  p.estimator.differencing.filter_cutoff_hz = 5.0;
  return p;
}

}  // namespace vmass::testing
