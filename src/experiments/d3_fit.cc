// SPDX-License-Identifier: Apache-2.0
// Decaying-sinusoid least squares and a plain DFT for experiment D3.
#include "d3_fit.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace mrh::experiments::internal {
namespace {

struct GridPoint {
  double f = 0.0, b = 0.0, error = std::numeric_limits<double>::infinity();
  double c_sin = 0.0, c_cos = 0.0;
};

// The best c_sin, c_cos of r ≈ e^(−Bτ)(c_sin sin ωτ + c_cos cos ωτ), by the 2×2 normal equations.
GridPoint Solve(const std::vector<double>& tau, const std::vector<double>& r, double f, double b) {
  const double w = 2.0 * std::numbers::pi * f;
  double ss = 0, sc = 0, cc = 0, rs = 0, rc = 0, rr = 0;
  for (std::size_t i = 0; i < tau.size(); ++i) {
    const double e = std::exp(-b * tau[i]);
    const double s = e * std::sin(w * tau[i]), c = e * std::cos(w * tau[i]);
    ss += s * s;
    sc += s * c;
    cc += c * c;
    rs += r[i] * s;
    rc += r[i] * c;
    rr += r[i] * r[i];
  }
  GridPoint p{f, b};
  const double det = ss * cc - sc * sc;
  if (!(std::abs(det) > 0.0)) return p;
  p.c_sin = (rs * cc - rc * sc) / det;
  p.c_cos = (rc * ss - rs * sc) / det;
  // Residual of a least-squares fit: |r|² − (projection of r).
  p.error = rr - (p.c_sin * rs + p.c_cos * rc);
  return p;
}

GridPoint Search(const std::vector<double>& tau, const std::vector<double>& r, double f0, double f1,
                 double df, double b0, double b1, double db) {
  GridPoint best;
  for (double f = f0; f <= f1; f += df) {
    for (double b = b0; b <= b1; b += db) {
      const GridPoint p = Solve(tau, r, f, b);
      if (p.error < best.error) best = p;
    }
  }
  return best;
}

}  // namespace

DecayFit FitDecayingSinusoid(const std::vector<double>& tau, const std::vector<double>& r,
                             double f_max) {
  constexpr double kCoarseDf = 1.0, kCoarseDb = 4.0;  // Hz, 1/s
  const GridPoint coarse = Search(tau, r, 1.0, f_max, kCoarseDf, 1.0, 400.0, kCoarseDb);
  const GridPoint fine =
      Search(tau, r, coarse.f - kCoarseDf, coarse.f + kCoarseDf, kCoarseDf / 100.0,
             std::max(0.1, coarse.b - kCoarseDb), coarse.b + kCoarseDb, kCoarseDb / 100.0);
  DecayFit fit;
  fit.frequency = fine.f;
  fit.decay = fine.b;
  fit.amplitude = std::hypot(fine.c_sin, fine.c_cos);
  fit.phase = std::atan2(fine.c_cos, fine.c_sin);
  fit.rms_error = std::sqrt(std::max(0.0, fine.error) / static_cast<double>(tau.size()));
  return fit;
}

std::vector<double> Spectrum(const std::vector<double>& r, double dt, double df, double f_max) {
  std::vector<double> out;
  for (double f = 0.0; f < f_max; f += df) {
    const double w = 2.0 * std::numbers::pi * f * dt;
    double re = 0.0, im = 0.0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      re += r[i] * std::cos(w * static_cast<double>(i));
      im -= r[i] * std::sin(w * static_cast<double>(i));
    }
    out.push_back(std::hypot(re, im) * dt);
  }
  return out;
}

}  // namespace mrh::experiments::internal
