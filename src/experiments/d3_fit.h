// SPDX-License-Identifier: Apache-2.0
// Fits a decaying sinusoid to a sampled force residual (experiment D3); knows no material.
#pragma once

#include <vector>

namespace mrh::experiments::internal {

/// r(τ) ≈ A e^(−B τ) sin(2π f τ + φ), fitted by least squares.
struct DecayFit {
  double frequency = 0.0;  ///< f (Hz)
  double decay = 0.0;      ///< B (1/s)
  double amplitude = 0.0;  ///< A (N)
  double phase = 0.0;      ///< φ (rad)
  double rms_error = 0.0;  ///< root-mean-square residual of the fit (N)
};

/// Least squares over samples (tau[i] s since onset, r[i] N): for every (f, B) on a grid
/// (f in [1, f_max] Hz, B in [1, 400] 1/s) the best A and φ are linear (r = e^(−Bτ)(c s + d c)),
/// then the best grid point is refined on a 100× finer grid around it. Not RT-safe.
DecayFit FitDecayingSinusoid(const std::vector<double>& tau, const std::vector<double>& r,
                             double f_max);

/// |DFT| of r at frequencies 0, df, 2 df, … < f_max (N·s: the sum times the sample period dt).
std::vector<double> Spectrum(const std::vector<double>& r, double dt, double df, double f_max);

}  // namespace mrh::experiments::internal
