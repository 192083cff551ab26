// SPDX-License-Identifier: Apache-2.0
// The contact local model's friction set follows the scene's cone: a resting box pushed
// horizontally with 0.8 μ m g. Analytic: the elliptic cone (a disc) holds it in every direction;
// MuJoCo's pyramid |f_t1| + |f_t2| <= μ f_n about the contact frame (t1 = y here) holds it along
// a frame axis (its vertex, μ m g) but not along a diagonal, where it gives μ m g / √2 only, so
// the box slides with a = (0.8 − 1/√2) μ g.
#include "mrh/render/local_contact_solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace mrh::render {
namespace {

constexpr double kMass = 0.5, kHalf = 0.05, kMu = 0.5, kG = 9.81, kDt = 0.001;

// A box (half sizes h) resting on the floor z = 0: four corner rows, MuJoCo's contact frame
// (n = z, t1 = y, as MuJoCo makes it for the floor).
ir::LocalContactModel BoxOnFloor(bool pyramidal, const Vec3& h = Vec3::Constant(kHalf)) {
  ir::LocalContactModel m;
  m.valid = true;
  m.gravity = Vec3(0, 0, -kG);
  ir::LocalIslandBody b;
  b.body = 1;
  b.motion = 0;
  b.mass = kMass;
  b.inertia_B = (kMass / 3.0) * Vec3(h.y() * h.y() + h.z() * h.z(), h.x() * h.x() + h.z() * h.z(),
                                     h.x() * h.x() + h.y() * h.y())
                                    .asDiagonal();
  b.X_WB = Pose{Vec3(0, 0, h.z()), Quat::Identity()};
  EXPECT_TRUE(m.bodies.PushBack(b));
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      ir::LocalContactRow r;
      r.a = 0;
      r.p_A = Vec3(sx * h.x(), sy * h.y(), -h.z());
      r.p_B = Vec3(sx * h.x(), sy * h.y(), 0.0);
      r.n_B = Vec3::UnitZ();
      r.t_B = Vec3::UnitY();
      r.mu = kMu;
      r.pyramidal = pyramidal;
      EXPECT_TRUE(m.contacts.PushBack(r));
    }
  }
  return m;
}

// The box's horizontal COM speed after settling 0.3 s and then `push_s` seconds of force F at its
// COM.
double SpeedAfterPush(bool pyramidal, const Vec3& F, double push_s) {
  LocalContactSolver solver;
  solver.Adopt(BoxOnFloor(pyramidal));
  for (int k = 0; k < 300; ++k) EXPECT_TRUE(solver.Step(kDt));
  const int n = static_cast<int>(std::lround(push_s / kDt));
  for (int k = 0; k < n; ++k) {
    solver.AddForce(0, F, solver.p_WCm(0));
    EXPECT_TRUE(solver.Step(kDt));
  }
  const Vec3 v = solver.V_WCm(0).v;
  return std::hypot(v.x(), v.y());
}

const double kPush = 0.8 * kMu * kMass * kG;  // N, below μ m g, above μ m g / √2
// The diagonal slide's speed after 0.5 s, a t with a = (0.8 − 1/√2) μ g: 0.23 m/s.
const double kSlide = (0.8 - std::sqrt(0.5)) * kMu * kG * 0.5;
// "Held": the soft contacts (MuJoCo's regularised friction, as in the reference) let a held box
// creep at about 1 mm/s; held means below 2 % of the slide's speed.
const double kHeld = 0.02 * kSlide;

TEST(LocalContactSolverFriction, EllipticConeHoldsTheBoxInEveryDirection) {
  EXPECT_LT(SpeedAfterPush(false, Vec3(kPush, 0, 0), 0.5), kHeld);
  EXPECT_LT(SpeedAfterPush(false, kPush * Vec3(1, 1, 0).normalized(), 0.5), kHeld);
}

TEST(LocalContactSolverFriction, PyramidHoldsAlongItsAxesAndSlidesAlongTheDiagonal) {
  EXPECT_LT(SpeedAfterPush(true, Vec3(kPush, 0, 0), 0.5), kHeld);
  EXPECT_LT(SpeedAfterPush(true, Vec3(0, kPush, 0), 0.5), kHeld);
  const double v = SpeedAfterPush(true, kPush * Vec3(1, -1, 0).normalized(), 0.5);
  EXPECT_NEAR(v, kSlide, 0.1 * kSlide);
}

// A 10 × 4 cm box (5 cm tall) resting on its four corner rows, elliptic cone, then thrown along a
// diagonal of the floor. Sliding, each corner's friction opposes its slip (maximum dissipation),
// so the box decelerates at μ g along its own track and does not start to spin. Its corners'
// tangents differ in effective mass (the lever arms to x and y differ), which is where a radial
// projection of the two friction impulses in the impulse metric turns friction off the slip.
TEST(LocalContactSolverFriction, EllipticConeOpposesTheSlipOfAnOblongBox) {
  LocalContactSolver solver;
  solver.Adopt(BoxOnFloor(false, Vec3(0.05, 0.02, 0.025)));
  for (int k = 0; k < 300; ++k) ASSERT_TRUE(solver.Step(kDt));
  const Vec3 dir = Vec3(1.0, 2.0, 0.0).normalized();
  constexpr double kV0 = 0.5;  // m/s
  solver.AddForce(0, kMass * kV0 / kDt * dir, solver.p_WCm(0));
  ASSERT_TRUE(solver.Step(kDt));
  const Vec3 v1 = solver.V_WCm(0).v;
  constexpr int kTicks = 50;
  for (int k = 0; k < kTicks; ++k) ASSERT_TRUE(solver.Step(kDt));
  const Vec3 v2 = solver.V_WCm(0).v;
  const Vec3 h1(v1.x(), v1.y(), 0.0), h2(v2.x(), v2.y(), 0.0);
  ASSERT_GT(h2.norm(), 0.2);  // still sliding
  EXPECT_LT(h1.normalized().cross(h2.normalized()).norm(), 1e-3) << "the track turned";
  EXPECT_LT(std::abs(solver.V_WCm(0).w.z()), 1e-2) << "the box started to spin";
  const double decel = (h1.norm() - h2.norm()) / (kTicks * kDt);
  EXPECT_NEAR(decel, kMu * kG, 0.02 * kMu * kG);
}

// A box pushed slowly along its own x axis, off its centre line, slides and turns. Coulomb's
// friction at the floor, a height z above it below the push, loads the front corners: the
// floor's centre of pressure lies x_p = μ z ahead of the centre (the pitch moment μ m g z over
// the weight m g). A body sliding and turning slowly (|ω| a ≪ v) has no lateral friction left
// only if it turns about the point abeam that centre of pressure: to first order in ω a / v the
// lateral friction is −μ Σ N_i (v_y + ω x_i) / v = −μ m g (v_y + ω x_p) / v, so its centre
// drifts sideways at v_y = −ω x_p. That drift moves the box's centre away from the pushing point
// and sets how fast an edge pushing near the centre line turns it; MuJoCo's soft contacts at
// 1 ms, whose sliding box hops, turn a box pushed at its centre's height about a point 1.2–1.7 cm
// ahead instead of 2.5 cm.
double TurningCentreAhead(double push_height) {
  LocalContactSolver solver;
  solver.Adopt(BoxOnFloor(false));
  for (int k = 0; k < 300; ++k) EXPECT_TRUE(solver.Step(kDt));
  // The push point on the -x face, 5 mm off the centre line; a velocity servo holds its speed
  // along the face normal at 2 cm/s (gain K: K dt / m = 0.4, a well-damped loop), slow enough
  // that the box's inertia is a small share of the friction (quasi-static).
  const Vec3 p_B(-kHalf, 0.005, push_height - kHalf);
  constexpr double kSpeed = 0.02, kGain = 200.0;  // m/s, N·s/m
  double v_y = 0.0, w_z = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const Pose X = solver.X_WB(0);
    const Vec3 p_W = X * p_B;
    const Vec3 x_W = X.q * Vec3::UnitX();
    const double f = std::max(0.0, kGain * (kSpeed - x_W.dot(solver.PointVelocity(0, p_W))));
    solver.AddForce(0, f * x_W, p_W);
    EXPECT_TRUE(solver.Step(kDt));
    if (k < 500) continue;  // settled into the steady slide
    v_y += (solver.X_WB(0).q.conjugate() * solver.V_WCm(0).v).y();
    w_z += solver.V_WCm(0).w.z();
  }
  EXPECT_LT(w_z, 0.0) << "the box did not turn away from the push";
  return v_y / -w_z;
}

TEST(LocalContactSolverFriction, OffCentrePushTurnsTheBoxAbeamItsCentreOfPressure) {
  // Push heights above the floor (m): the centre's, and 3 cm below and above it (the back
  // corners keep a tenth of the weight at the highest).
  for (const double z : {kHalf, kHalf - 0.03, kHalf + 0.03}) {
    const double x_p = kMu * z;
    // 5 %: the first-order formula (the exact quasi-static solution of these four corners is
    // 0.4 % above it at the centre's height) and the box's inertia at 2 cm/s (about 1 %).
    EXPECT_NEAR(TurningCentreAhead(z), x_p, 0.05 * x_p) << "push at " << z << " m";
  }
}

// Restart: a caller whose world owns the bodies (proxy-6dof's physics-side island) hands the
// solver its state every period. The bodies start from it, not from the solver's own run, and
// the contacts keep their impulses, so a sliding, turning box re-exported every tick moves as
// one continuous run does and its solve converges; from zero impulses (Clear, then Adopt) it
// stops at the sweep cap every tick.
TEST(LocalContactSolverRestart, StartsFromTheExportedStateWithWarmContacts) {
  const auto exported = [](const LocalContactSolver& from) {
    ir::LocalContactModel m = BoxOnFloor(false);
    m.bodies[0].X_WB = from.X_WB(0);
    m.bodies[0].V_WCm = from.V_WCm(0);
    return m;
  };
  const LocalContactSolverSettings settings;
  LocalContactSolver continuous(settings);
  continuous.Adopt(BoxOnFloor(false));
  for (int k = 0; k < 300; ++k) EXPECT_TRUE(continuous.Step(kDt));
  LocalContactSolver restarted = continuous, cold = continuous;
  // 1.2 μ m g along +x at the -x face, 3 cm off the centre line: the box slides and turns.
  const Vec3 p_B(-kHalf, 0.03, 0.0);
  const Vec3 F(1.2 * kMu * kMass * kG, 0.0, 0.0);
  int continuous_capped = 0, cold_capped = 0, sweeps_differ = 0;
  for (int k = 0; k < 300; ++k) {
    restarted.Restart(exported(restarted));
    cold.Clear();
    cold.Adopt(exported(cold));
    for (LocalContactSolver* s : {&continuous, &restarted, &cold}) {
      s->AddForce(0, s->X_WB(0).q * F, s->X_WB(0) * p_B);
      EXPECT_TRUE(s->Step(kDt));
    }
    continuous_capped += continuous.last_sweeps() == settings.iterations ? 1 : 0;
    cold_capped += cold.last_sweeps() == settings.iterations ? 1 : 0;
    sweeps_differ += restarted.last_sweeps() != continuous.last_sweeps() ? 1 : 0;
  }
  EXPECT_LT(continuous.V_WCm(0).w.z(), -0.1) << "the push did not turn the box";
  EXPECT_LT((restarted.p_WCm(0) - continuous.p_WCm(0)).norm(), 1e-9);
  EXPECT_NEAR(restarted.V_WCm(0).w.z(), continuous.V_WCm(0).w.z(), 1e-6);
  // The same solve tick by tick; cold, nearly every tick stops at the cap (the continuous run
  // reaches it in a quarter of them as the box starts to slide and turn).
  EXPECT_EQ(sweeps_differ, 0);
  EXPECT_LT(continuous_capped, 100);
  EXPECT_GT(cold_capped, 250);

  // Not the solver's own run: a body moved by the world between periods starts where it is.
  ir::LocalContactModel moved = exported(restarted);
  moved.bodies[0].X_WB.p.x() += 0.01;
  const Vec3 p_moved = moved.bodies[0].X_WB * moved.bodies[0].p_BCm;
  restarted.Restart(moved);
  EXPECT_LT((restarted.p_WCm(0) - p_moved).norm(), 1e-12);
}

}  // namespace
}  // namespace mrh::render
