// SPDX-License-Identifier: Apache-2.0
// FitLogistic against an independent computation, simulated observers of known θ, and the data
// that have no ML estimate.
#include "mrh/psychophysics/logistic_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "mrh/core/error.h"

namespace mrh::psychophysics {
namespace {

constexpr double kRelative = 1e-6;

void ExpectRelative(double actual, double expected, const char* what) {
  EXPECT_NEAR(actual, expected, kRelative * std::abs(expected)) << what;
}

// Reference values from this python3 (stdlib only) script: a plain Newton–Raphson on the raw
// (θ1, θ2), written apart from the library (no centring, no step halving, its own stopping rule):
//
//   import math
//   def fit(data, std):
//       t1, t2 = 0.0, 0.0
//       for _ in range(200):
//           g1=g2=a=b=c=0.0
//           for m,n,k in data:
//               p=1/(1+math.exp(-(t1+t2*m)))
//               g1+=k-n*p; g2+=(k-n*p)*m
//               w=n*p*(1-p); a+=w; b+=w*m; c+=w*m*m
//           det=a*c-b*b
//           d1=( c*g1-b*g2)/det; d2=(-b*g1+a*g2)/det
//           t1+=d1; t2+=d2
//           if abs(d1)<1e-15*(1+abs(t1)) and abs(d2)<1e-15*(1+abs(t2)): break
//       a=b=c=0.0
//       for m,n,k in data:
//           p=1/(1+math.exp(-(t1+t2*m))); w=n*p*(1-p); a+=w; b+=w*m; c+=w*m*m
//       det=a*c-b*b; v11=c/det; v22=a/det; v12=-b/det
//       pse=-t1/t2; j1=-1/t2; j2=t1/t2**2
//       var=j1*j1*v11+2*j1*j2*v12+j2*j2*v22
//       chi2=(pse-std)**2/var
//       p=math.erfc(math.sqrt(chi2/2))
//       return t1,t2,pse,math.sqrt(var),chi2,p
//   A=[(30,20,2),(45,20,5),(60,20,9),(75,20,12),(90,20,16),(105,20,18)]
//   B=[(30,20,9),(45,20,14),(60,20,17),(75,20,19),(90,20,19),(105,20,20)]
//   for d in (A,B):
//       print(", ".join("%.17g"%x for x in fit(d,60.0)))
struct Reference {
  std::vector<Observation> data;
  double theta1, theta2, pse, pse_sd, chi2, p;
};

const Reference kReferences[] = {
    {{{30, 20, 2}, {45, 20, 5}, {60, 20, 9}, {75, 20, 12}, {90, 20, 16}, {105, 20, 18}},
     -3.699372802144909,
     0.056266297306463056,
     65.74757855480884,
     3.9492068042125381,
     2.1181176451730912,
     0.14556535434722156},
    {{{30, 20, 9}, {45, 20, 14}, {60, 20, 17}, {75, 20, 19}, {90, 20, 19}, {105, 20, 20}},
     -2.0700824146953125,
     0.06356419264436515,
     32.566801033361692,
     5.5287544240187456,
     24.620581546286566,
     6.980222818093175e-07},
};

TEST(LogisticFitTest, MatchesAnIndependentNewtonRaphsonTo1e6Relative) {
  for (const Reference& r : kReferences) {
    const PsychometricFit f = FitLogistic(r.data, 60.0);
    ASSERT_EQ(f.status, FitStatus::kOk);
    EXPECT_EQ(f.trials, 120);
    ExpectRelative(f.theta1, r.theta1, "theta1");
    ExpectRelative(f.theta2, r.theta2, "theta2");
    ExpectRelative(f.pse, r.pse, "pse");
    ExpectRelative(f.pse_sd, r.pse_sd, "pse_sd");
    ExpectRelative(f.chi2, r.chi2, "chi2");
    ExpectRelative(f.p, r.p, "p");
  }
}

// The score equations hold at the optimum: Σ (yes − n p) = 0 and Σ (yes − n p) m = 0.
TEST(LogisticFitTest, ScoreIsZeroAtTheOptimum) {
  const Reference& r = kReferences[0];
  const PsychometricFit f = FitLogistic(r.data, 60.0);
  double g1 = 0.0, g2 = 0.0;
  for (const Observation& o : r.data) {
    const double p = 1.0 / (1.0 + std::exp(-(f.theta1 + f.theta2 * o.mass)));
    g1 += o.yes - o.n * p;
    g2 += (o.yes - o.n * p) * o.mass;
  }
  EXPECT_NEAR(g1, 0.0, 1e-9);
  EXPECT_NEAR(g2, 0.0, 1e-7);
}

// Two levels fit exactly: P̂ equals the observed fractions, so θ has a closed form.
TEST(LogisticFitTest, TwoLevelsGiveTheClosedFormLogits) {
  const std::vector<Observation> data{{40, 10, 2}, {80, 10, 7}};
  const PsychometricFit f = FitLogistic(data, 60.0);
  ASSERT_EQ(f.status, FitStatus::kOk);
  const double l1 = std::log(0.2 / 0.8), l2 = std::log(0.7 / 0.3);
  const double theta2 = (l2 - l1) / 40.0;
  ExpectRelative(f.theta2, theta2, "theta2");
  ExpectRelative(f.theta1, l1 - theta2 * 40.0, "theta1");
  // Var(logit p̂) = 1 / (n p (1 − p)) at each level, independent: the delta method by hand.
  const double v1 = 1.0 / (10 * 0.2 * 0.8), v2 = 1.0 / (10 * 0.7 * 0.3);
  ExpectRelative(f.var_theta2, (v1 + v2) / 1600.0, "var theta2");
}

// Simulated observers of known θ: the estimates are unbiased to a few standard errors, and the
// delta-method interval PSE ± 1.96 SD covers the true PSE in ~95 % of replications.
TEST(LogisticFitTest, SimulatedObserversRecoverTheirPseWithCalibratedIntervals) {
  const double theta1 = -6.0, theta2 = 0.1;  // PSE 60 kg, the standard
  const double masses[] = {30, 45, 60, 75, 90, 105};
  std::mt19937_64 rng(20261201);
  constexpr int kReplications = 400;
  int covered = 0;
  double p_sum = 0.0, pse_sum = 0.0;
  for (int rep = 0; rep < kReplications; ++rep) {
    std::vector<Observation> data;
    for (const double m : masses) {
      std::binomial_distribution<int> answers(50, 1.0 / (1.0 + std::exp(-(theta1 + theta2 * m))));
      data.push_back({m, 50, answers(rng)});
    }
    const PsychometricFit f = FitLogistic(data, 60.0);
    ASSERT_EQ(f.status, FitStatus::kOk) << rep;
    covered += std::abs(f.pse - 60.0) <= 1.96 * f.pse_sd ? 1 : 0;
    p_sum += f.p;
    pse_sum += f.pse;
  }
  // Binomial SD of the coverage over 400 replications: sqrt(.95·.05/400) = 0.011; 3 SD bounds.
  EXPECT_NEAR(covered / double(kReplications), 0.95, 0.033);
  // Under the null the p-value is uniform: mean 0.5, SD of the mean 0.29/sqrt(400) = 0.014.
  EXPECT_NEAR(p_sum / kReplications, 0.5, 0.045);
  EXPECT_NEAR(pse_sum / kReplications, 60.0, 0.5);
}

TEST(LogisticFitTest, OneLargeSimulatedRunRecoversTheta) {
  const double theta1 = 4.0, theta2 = -0.08;  // a decreasing function is fitted too
  std::mt19937_64 rng(7);
  std::vector<Observation> data;
  for (double m = 20; m <= 80; m += 10) {
    std::binomial_distribution<int> answers(5000, 1.0 / (1.0 + std::exp(-(theta1 + theta2 * m))));
    data.push_back({m, 5000, answers(rng)});
  }
  const PsychometricFit f = FitLogistic(data, 50.0);
  ASSERT_EQ(f.status, FitStatus::kOk);
  EXPECT_NEAR(f.theta1, theta1, 4.0 * std::sqrt(f.var_theta1));
  EXPECT_NEAR(f.theta2, theta2, 4.0 * std::sqrt(f.var_theta2));
  EXPECT_NEAR(f.pse, 50.0, 4.0 * f.pse_sd);
}

TEST(LogisticFitTest, DataWithoutAFiniteMaximumAreReportedNotFitted) {
  struct Case {
    std::vector<Observation> data;
    FitStatus status;
  };

  const Case cases[] = {
      {{}, FitStatus::kNoTrials},
      {{{30, 0, 0}}, FitStatus::kNoTrials},
      {{{30, 20, 0}, {60, 20, 0}, {90, 20, 0}}, FitStatus::kAllSame},
      {{{30, 20, 20}, {60, 20, 20}}, FitStatus::kAllSame},
      {{{60, 20, 7}}, FitStatus::kOneLevel},
      {{{30, 20, 0}, {60, 20, 0}, {90, 20, 20}}, FitStatus::kSeparable},
      {{{30, 20, 0}, {60, 20, 5}, {90, 20, 20}}, FitStatus::kSeparable},   // quasi-complete
      {{{30, 20, 20}, {60, 20, 20}, {90, 20, 3}}, FitStatus::kSeparable},  // decreasing
  };
  for (const Case& c : cases) {
    const PsychometricFit f = FitLogistic(c.data, 60.0);
    EXPECT_EQ(f.status, c.status) << FitStatusName(f.status);
    for (const double v : {f.theta1, f.theta2, f.pse, f.pse_sd, f.chi2, f.p}) {
      EXPECT_EQ(v, 0.0);  // never NaN or infinite
    }
  }
}

TEST(LogisticFitTest, BadObservationsAreErrors) {
  const std::vector<Observation> bad{{30, 5, 6}};
  EXPECT_THROW((void)FitLogistic(bad, 60.0), InvalidArgument);
  const std::vector<Observation> nan{{std::nan(""), 5, 1}};
  EXPECT_THROW((void)FitLogistic(nan, 60.0), InvalidArgument);
}

TEST(LogisticFitTest, ChiSquareSurvivalMatchesTheNormalTails) {
  // χ²₁ = Z²: P(χ² >= 1.959964²) = P(|Z| >= 1.959964) = 0.05.
  EXPECT_NEAR(ChiSquare1Survival(1.959963984540054 * 1.959963984540054), 0.05, 1e-12);
  EXPECT_DOUBLE_EQ(ChiSquare1Survival(0.0), 1.0);
}

}  // namespace
}  // namespace mrh::psychophysics
