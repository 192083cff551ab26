// SPDX-License-Identifier: Apache-2.0
// render::CouplingGrowthPerTick against the recurrence it claims to describe, iterated directly.
#include "mrh/render/virtual_coupling.h"

#include <gtest/gtest.h>

#include <cmath>

namespace mrh::render {
namespace {

// The coupled axis iterated as the schedule runs it: x_{k+1} − 2x_k + x_{k−1} =
// −a x_{k−1} − c (x_{k−1} − x_{k−2}), from a unit displacement at rest. Returns the largest |x|
// over the last 100 of `steps` ticks, or the first |x| above 1e100.
double TailAmplitude(double a, double c, int steps) {
  double x2 = 1.0, x1 = 1.0, x0 = 1.0;  // x_{k−2}, x_{k−1}, x_k
  double tail = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double next = 2.0 * x0 - x1 - a * x1 - c * (x1 - x2);
    x2 = x1;
    x1 = x0;
    x0 = next;
    if (std::abs(x0) > 1e100) return std::abs(x0);  // grown beyond doubt (and before overflow)
    if (k >= steps - 100) tail = std::max(tail, std::abs(x0));
  }
  return tail;
}

TEST(CouplingGrowthTest, UncoupledToolOnlyDrifts) {
  EXPECT_NEAR(CouplingGrowthPerTick(0.0, 0.0), 1.0, 1e-6);
}

TEST(CouplingGrowthTest, UndampedCouplingGrowsAsOnePlusA) {
  // c = 0: z² − 2z + (1 + a) = 0 besides z = 0, so |z| = √(1 + a).
  for (double a : {0.01, 0.1, 0.5}) {
    EXPECT_NEAR(CouplingGrowthPerTick(a, 0.0), std::sqrt(1.0 + a), 1e-9);
  }
}

TEST(CouplingGrowthTest, ClassifiesEveryGainPairAsTheIteratedLoopBehaves) {
  int stable = 0, unstable = 0;
  for (double a : {1e-4, 1e-3, 0.01, 0.05, 0.1, 0.2, 0.5, 0.8}) {
    for (double c : {0.01, 0.05, 0.1, 0.3, 0.5, 0.8, 1.0, 2.0, 8.0}) {
      const double growth = CouplingGrowthPerTick(a, c);
      const int steps = 3000;
      const double tail = TailAmplitude(a, c, steps);
      // The tail follows growth^k up to a modest factor (and a factor k where roots nearly
      // coincide): compare per-tick rates where the tail neither underflows nor escaped.
      if (tail > 1e-200 && tail < 1e100) {
        EXPECT_NEAR(std::pow(tail, 1.0 / steps), growth, 5e-3) << "a " << a << " c " << c;
      }
      if (growth < 0.999) {
        ++stable;
        EXPECT_LT(tail, 1e-1) << "a " << a << " c " << c;
      } else if (growth > 1.001) {
        ++unstable;
        EXPECT_GT(tail, 10.0) << "a " << a << " c " << c;
      }
    }
  }
  EXPECT_GT(stable, 10);
  EXPECT_GT(unstable, 10);
}

}  // namespace
}  // namespace mrh::render
