// SPDX-License-Identifier: Apache-2.0
// Maximum-likelihood logistic psychometric function, its PSE and the PSE's χ² test (thesis §4.5.4).
#pragma once

#include <span>
#include <string>

namespace mrh::psychophysics {

/// The answers at one comparison mass: `yes` of `n` trials said "the comparison was heavier".
struct Observation {
  double mass = 0.0;  ///< kg, the comparison stimulus
  int n = 0;          ///< trials (>= 0)
  int yes = 0;        ///< answers "comparison heavier" (0 <= yes <= n)
};

/// Why a fit has (or has no) estimates.
enum class FitStatus {
  kOk,            ///< the likelihood has a finite maximum; every estimate is set
  kNoTrials,      ///< no observation with n > 0
  kAllSame,       ///< every answer is equal: P is 0 or 1 everywhere, no slope can be estimated
  kOneLevel,      ///< answers vary at one mass only: the slope is not identifiable
  kSeparable,     ///< a mass splits the answers (quasi-)completely: the ML slope is infinite
  kNotConverged,  ///< Newton–Raphson did not converge in kMaxIterations
};

/// "ok", "no trials", "all answers equal", "one mass level", "separable", "not converged".
const char* FitStatusName(FitStatus status) noexcept;

/// The fit of P(comparison heavier | m) = 1 / (1 + exp(−(θ1 + θ2 m))) and what follows from it.
/// Only `status`, `trials` and `standard_mass` are meaningful unless status == kOk; the others
/// are then 0 (never NaN).
struct PsychometricFit {
  FitStatus status = FitStatus::kNoTrials;
  int trials = 0;                                                ///< Σ n
  double standard_mass = 0.0;                                    ///< kg
  double theta1 = 0.0;                                           ///< 1
  double theta2 = 0.0;                                           ///< 1/kg
  double var_theta1 = 0.0, var_theta2 = 0.0, cov_theta12 = 0.0;  ///< inverse Fisher information
  double pse = 0.0;                                              ///< kg, −θ1/θ2: where P = 1/2
  double pse_sd = 0.0;  ///< kg, delta-method standard deviation of the PSE
  double chi2 = 0.0;    ///< (PSE − standard)² / Var(PSE), 1 degree of freedom
  double p = 0.0;       ///< P(χ²₁ >= chi2)
  int iterations = 0;   ///< Newton–Raphson iterations used
};

/// Newton–Raphson iterations at most; a well-posed fit converges in < 10.
inline constexpr int kMaxIterations = 100;

/// Fits the logistic function by maximum likelihood (Newton–Raphson on (θ1, θ2) with step
/// halving), then PSE = −θ1/θ2, Var(PSE) = ∇PSEᵀ I⁻¹ ∇PSE with ∇PSE = (−1/θ2, θ1/θ2²) and I the
/// Fisher information at the optimum, χ² = (PSE − standard_mass)² / Var(PSE) and its p-value
/// (Nagai, Hoshino & Uchikawa 2006). Data without a finite maximum (see FitStatus) are reported
/// by the status, not fitted. Observations with n = 0 are ignored; masses may repeat.
/// @throws mrh::InvalidArgument if an observation has n < 0, yes outside [0, n] or a mass that
/// is not finite, or if standard_mass is not finite. Not RT-safe (allocates nothing, though).
PsychometricFit FitLogistic(std::span<const Observation> data, double standard_mass);

/// P(X >= chi2) for X ~ χ² with 1 degree of freedom: erfc(sqrt(chi2 / 2)). chi2 >= 0.
double ChiSquare1Survival(double chi2) noexcept;

}  // namespace mrh::psychophysics
