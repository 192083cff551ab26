// SPDX-License-Identifier: Apache-2.0
// FitLogistic: the data checks that decide whether an ML fit exists, Newton–Raphson, delta method.
#include "mrh/psychophysics/logistic_fit.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "mrh/core/error.h"

namespace mrh::psychophysics {
namespace {

// Newton–Raphson stops when a step moves the scaled parameters by less than this: they are O(1)
// to O(10), so this is ~1e4 ulps, far below the 1e-6 the analysis is checked to.
constexpr double kStepTolerance = 1e-12;
// Step halvings per iteration at most (the log-likelihood is concave, so 1-2 are the rule).
constexpr int kMaxHalvings = 60;

void Check(std::span<const Observation> data, double standard_mass) {
  if (!std::isfinite(standard_mass)) {
    throw InvalidArgument(
        fmt::format("standard mass = {}; expected a finite mass in kg", standard_mass));
  }
  for (const Observation& o : data) {
    if (!std::isfinite(o.mass) || o.n < 0 || o.yes < 0 || o.yes > o.n) {
      throw InvalidArgument(fmt::format(
          "observation mass = {} kg, n = {}, yes = {}; expected a finite mass and 0 <= yes <= n",
          o.mass, o.n, o.yes));
    }
  }
}

// In one dimension the ML estimate is infinite exactly when some mass c has every "no" at m <= c
// and every "yes" at m >= c (or the mirror image): then a steeper and steeper logistic through c
// keeps raising the likelihood (Albert & Anderson 1984).
FitStatus Classify(std::span<const Observation> data) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double min_yes = kInf, max_yes = -kInf, min_no = kInf, max_no = -kInf;
  int trials = 0, yes = 0;
  for (const Observation& o : data) {
    if (o.n == 0) continue;
    trials += o.n;
    yes += o.yes;
    if (o.yes > 0) min_yes = std::min(min_yes, o.mass), max_yes = std::max(max_yes, o.mass);
    if (o.yes < o.n) min_no = std::min(min_no, o.mass), max_no = std::max(max_no, o.mass);
  }
  if (trials == 0) return FitStatus::kNoTrials;
  if (yes == 0 || yes == trials) return FitStatus::kAllSame;
  // Distinct masses that carry answers: one only means the slope cannot be estimated.
  if (min_yes == max_yes && min_no == max_no && min_yes == min_no) return FitStatus::kOneLevel;
  if (min_yes >= max_no || max_yes <= min_no) return FitStatus::kSeparable;
  return FitStatus::kOk;
}

// Log-likelihood, gradient and Fisher information of (b0, b1) for P = σ(b0 + b1 x), x = (m−c)/s.
struct Local {
  double log_likelihood = 0.0;
  double g0 = 0.0, g1 = 0.0;
  double i00 = 0.0, i01 = 0.0, i11 = 0.0;
};

// log σ(z) and log(1 − σ(z)) without overflow.
double LogSigmoid(double z) {
  return z >= 0 ? -std::log1p(std::exp(-z)) : z - std::log1p(std::exp(z));
}

Local Evaluate(std::span<const Observation> data, double c, double s, double b0, double b1) {
  Local l;
  for (const Observation& o : data) {
    if (o.n == 0) continue;
    const double x = (o.mass - c) / s;
    const double z = b0 + b1 * x;
    const double p = 1.0 / (1.0 + std::exp(-z));
    l.log_likelihood += o.yes * LogSigmoid(z) + (o.n - o.yes) * LogSigmoid(-z);
    const double r = o.yes - o.n * p;
    l.g0 += r;
    l.g1 += r * x;
    const double w = o.n * p * (1.0 - p);
    l.i00 += w;
    l.i01 += w * x;
    l.i11 += w * x * x;
  }
  return l;
}

// Newton–Raphson with step halving on the scaled problem; returns iterations, or -1.
int Maximize(std::span<const Observation> data, double c, double s, double* b0, double* b1) {
  Local l = Evaluate(data, c, s, *b0, *b1);
  for (int it = 1; it <= kMaxIterations; ++it) {
    const double det = l.i00 * l.i11 - l.i01 * l.i01;
    if (!(det > 0.0)) return -1;
    double d0 = (l.i11 * l.g0 - l.i01 * l.g1) / det;
    double d1 = (l.i00 * l.g1 - l.i01 * l.g0) / det;
    Local next = Evaluate(data, c, s, *b0 + d0, *b1 + d1);
    for (int h = 0; h < kMaxHalvings && next.log_likelihood < l.log_likelihood; ++h) {
      d0 *= 0.5, d1 *= 0.5;
      next = Evaluate(data, c, s, *b0 + d0, *b1 + d1);
    }
    *b0 += d0, *b1 += d1;
    l = next;
    if (std::max(std::abs(d0), std::abs(d1)) < kStepTolerance) return it;
  }
  return -1;
}

// θ, the inverse Fisher information in θ, the PSE and its test, from the scaled optimum.
void Finish(std::span<const Observation> data, double c, double s, double b0, double b1,
            PsychometricFit* fit) {
  fit->theta2 = b1 / s;
  fit->theta1 = b0 - b1 * c / s;
  const Local l = Evaluate(data, 0.0, 1.0, fit->theta1, fit->theta2);  // information in θ
  const double det = l.i00 * l.i11 - l.i01 * l.i01;
  fit->var_theta1 = l.i11 / det;
  fit->var_theta2 = l.i00 / det;
  fit->cov_theta12 = -l.i01 / det;
  fit->pse = -fit->theta1 / fit->theta2;
  const double d1 = -1.0 / fit->theta2;
  const double d2 = fit->theta1 / (fit->theta2 * fit->theta2);
  const double var =
      d1 * d1 * fit->var_theta1 + 2.0 * d1 * d2 * fit->cov_theta12 + d2 * d2 * fit->var_theta2;
  fit->pse_sd = std::sqrt(var);
  const double diff = fit->pse - fit->standard_mass;
  fit->chi2 = diff * diff / var;
  fit->p = ChiSquare1Survival(fit->chi2);
}

}  // namespace

const char* FitStatusName(FitStatus status) noexcept {
  switch (status) {
    case FitStatus::kOk:
      return "ok";
    case FitStatus::kNoTrials:
      return "no trials";
    case FitStatus::kAllSame:
      return "all answers equal";
    case FitStatus::kOneLevel:
      return "one mass level";
    case FitStatus::kSeparable:
      return "separable";
    case FitStatus::kNotConverged:
      return "not converged";
  }
  return "?";
}

double ChiSquare1Survival(double chi2) noexcept {
  return std::erfc(std::sqrt(0.5 * chi2));
}

PsychometricFit FitLogistic(std::span<const Observation> data, double standard_mass) {
  Check(data, standard_mass);
  PsychometricFit fit;
  fit.standard_mass = standard_mass;
  for (const Observation& o : data) fit.trials += o.n;
  fit.status = Classify(data);
  if (fit.status != FitStatus::kOk) return fit;
  // Centre and scale the masses (trial-weighted mean and standard deviation) so that the
  // Newton steps are well conditioned whatever the mass unit range.
  double c = 0.0, s2 = 0.0;
  for (const Observation& o : data) c += o.n * o.mass;
  c /= fit.trials;
  for (const Observation& o : data) s2 += o.n * (o.mass - c) * (o.mass - c);
  const double s = std::sqrt(s2 / fit.trials);
  double b0 = 0.0, b1 = 0.0;
  fit.iterations = Maximize(data, c, s, &b0, &b1);
  if (fit.iterations < 0 || !std::isfinite(b0) || !std::isfinite(b1) || b1 == 0.0) {
    fit.status = FitStatus::kNotConverged;
    fit.iterations = kMaxIterations;
    return fit;
  }
  Finish(data, c, s, b0, b1, &fit);
  if (!std::isfinite(fit.pse_sd) || !std::isfinite(fit.chi2)) {
    const int iterations = fit.iterations;
    fit = PsychometricFit{.status = FitStatus::kNotConverged,
                          .trials = fit.trials,
                          .standard_mass = standard_mass,
                          .iterations = iterations};
  }
  return fit;
}

}  // namespace mrh::psychophysics
