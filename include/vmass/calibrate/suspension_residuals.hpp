// Residual functors of the rear-suspension calibration, in the shape of Ceres' examples: small
// templated functors, one per model, with a Create() factory returning an autodiff cost.
//
// THIS HEADER INCLUDES CERES (about 20 s of compile time per translation unit): include it only
// in the calibration's own sources and tests, never from a header others use.
//
// Units inside the fit: deflection in mm, force in N, so stiffness comes out in N/mm (= kN/m)
// and the progressive rate in N/mm^2 (= 1e6 N/m^2); all parameters are then of order 1..100 and
// the normal equations are well conditioned. Each residual is a deflection error in mm: the
// ballast masses (hence the forces F = dM g l_f / (2 l), see load_geometry.hpp) are known
// exactly, the sensor reading is what carries the noise.
//
// Linear model, eq. (3) of the paper with the sensor's zero offset z0:
//   z(F) = z0 + F / c
//   r    = z_meas - z(F)                    parameters: z0 [mm], c [N/mm]
//
// Progressive model: the linear spring plus a bump stop beyond a knee, the curve the static
// initialisation inverts (SuspensionParams::wheel_force_n):
//   F(z) = c (z - z0) + k2 max(0, z - z_knee)^2,      z_knee = z0 + d,  d >= 0
// inverted in closed form (the quadratic's stable root):
//   z(F) = z0 + F / c                                          F <= c d
//   z(F) = z0 + d + 2 R / (c + sqrt(c^2 + 4 k2 R)),  R = F - c d   F >  c d
//   r    = z_meas - z(F)                    parameters: z0 [mm], c [N/mm], d [mm], k2 [N/mm^2]
// The knee offset d (rather than z_knee) keeps the knee above the empty reading with a simple
// bound d >= 0. z(F) is continuously differentiable in F and in every parameter (at R = 0 both
// branches have dz/dF = 1/c and dz/dd = 0); only second derivatives jump at the knee. How the
// fit copes with that is explained in suspension_fit.hpp.
//
// Thread-safe (immutable after construction).
#pragma once

#include <cmath>

#include <ceres/ceres.h>

namespace vmass::calibrate {

struct LinearDeflectionResidual {
  LinearDeflectionResidual(double force_n, double deflection_mm)
      : force_n_(force_n), deflection_mm_(deflection_mm) {}

  template <typename T>
  bool operator()(const T* const z0_mm, const T* const c_n_per_mm, T* residual) const {
    if (!(c_n_per_mm[0] > T(0.0))) return false;
    residual[0] = T(deflection_mm_) - (z0_mm[0] + T(force_n_) / c_n_per_mm[0]);
    return true;
  }

  static ceres::CostFunction* Create(double force_n, double deflection_mm) {
    return new ceres::AutoDiffCostFunction<LinearDeflectionResidual, 1, 1, 1>(
        new LinearDeflectionResidual(force_n, deflection_mm));
  }

 private:
  double force_n_;
  double deflection_mm_;
};

struct ProgressiveDeflectionResidual {
  ProgressiveDeflectionResidual(double force_n, double deflection_mm)
      : force_n_(force_n), deflection_mm_(deflection_mm) {}

  /// z(F) of the header comment, for any scalar type (double or ceres::Jet).
  template <typename T>
  static T predicted_deflection_mm(const T& force_n, const T& z0_mm, const T& c_n_per_mm,
                                   const T& knee_offset_mm, const T& k2_n_per_mm2) {
    using std::sqrt;
    const T knee_force_n = c_n_per_mm * knee_offset_mm;
    if (force_n <= knee_force_n) return z0_mm + force_n / c_n_per_mm;
    const T beyond_n = force_n - knee_force_n;
    return z0_mm + knee_offset_mm +
           T(2.0) * beyond_n /
               (c_n_per_mm + sqrt(c_n_per_mm * c_n_per_mm + T(4.0) * k2_n_per_mm2 * beyond_n));
  }

  template <typename T>
  bool operator()(const T* const z0_mm, const T* const c_n_per_mm, const T* const knee_offset_mm,
                  const T* const k2_n_per_mm2, T* residual) const {
    if (!(c_n_per_mm[0] > T(0.0)) || k2_n_per_mm2[0] < T(0.0)) return false;
    residual[0] = T(deflection_mm_) - predicted_deflection_mm(T(force_n_), z0_mm[0], c_n_per_mm[0],
                                                              knee_offset_mm[0], k2_n_per_mm2[0]);
    return true;
  }

  static ceres::CostFunction* Create(double force_n, double deflection_mm) {
    return new ceres::AutoDiffCostFunction<ProgressiveDeflectionResidual, 1, 1, 1, 1, 1>(
        new ProgressiveDeflectionResidual(force_n, deflection_mm));
  }

 private:
  double force_n_;
  double deflection_mm_;
};

}  // namespace vmass::calibrate
