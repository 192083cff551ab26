// SPDX-License-Identifier: Apache-2.0
// Tests of the 6-DOF proxy's contact torque model: the felt wrench and every object's reaction
// are one set of contact forces, inside each object's friction cone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/render/proxy_renderer.h"
#include "proxy_rig.h"

namespace mrh::render {
namespace {

using namespace proxy_rig;  // NOLINT(google-build-using-namespace): the test vocabulary

ProxyRendererSettings Contact(double mu) {
  return ProxyRendererSettings{.k_t = kKt,
                               .k_r = 20.0,
                               .mu = mu,
                               .torque_model = ProxyTorqueModel::kContact,
                               .max_iterations = kSolverBudget,
                               .tolerance = kSolverTol};
}

// Moment about `point` of a wrench whose torque is about `about`.
Vec3 MomentAbout(const Wrench& w, const Vec3& about, const Vec3& point) {
  return w.tau + (about - point).cross(w.f);
}

TEST(ProxyContactModelTest, ReactionsOfSeveralObjectsAreMinusTheFeltWrenchAboutAnyPoint) {
  // Two moving boxes under a twisted, sliding face with friction and a damper: every force is a
  // contact force, so the reactions and the felt wrench cancel about any point, not only about
  // the pointer origin.
  ProxyRendererSettings settings = Contact(kMu);
  settings.d_t = 10.0;
  Rig rig(settings);
  auto specs = [] {
    PairSpec left = Box(5, Pose{});
    left.points_P = {Vec3(-kHalf, kHalf, -kHalf), Vec3(-kHalf, -kHalf, -kHalf)};
    PairSpec right = Box(6, Pose{});
    right.key = 10;
    right.p_BCm = Vec3(0.3, -0.1, -0.2);
    right.points_P = {Vec3(kHalf, kHalf, -kHalf)};
    return std::vector<PairSpec>{left, right};
  };
  (void)rig.Tick(specs(), Pressed());
  const Pose X_WP = Pressed(Vec3(2e-4, 1e-4, -1e-4), About(Vec3::UnitZ(), 0.01));
  const ProxyOutput& out = rig.Tick(specs(), X_WP);
  ASSERT_EQ(out.reactions.size(), 2u);
  ASSERT_GT(out.diagnostics.sliding_rows + out.diagnostics.sticking_rows, 0);
  const auto centre_of_mass = [](int body) {
    return body == 5 ? Vec3(0, 0, -0.05) : Vec3(0.3, -0.1, -0.2);
  };
  for (const Vec3& point : {Vec3(0.0, 0.0, 0.0), Vec3(1.0, -2.0, 0.5)}) {
    Vec3 force = Vec3::Zero();
    Vec3 moment = Vec3::Zero();
    for (const ProxyPairReaction& r : out.reactions) {
      force -= r.w_W.f;
      moment -= MomentAbout(r.w_W, centre_of_mass(r.body), point);
    }
    EXPECT_LT((force - out.w_W.f).norm(), 1e-9 * out.w_W.f.norm());
    EXPECT_LT((moment - MomentAbout(out.w_W, X_WP.p, point)).norm(),
              1e-9 * out.w_W.f.norm() * (1.0 + point.norm()));
  }
}

TEST(ProxyContactModelTest, APointContactGivesItsObjectNoCouple) {
  // A sphere touched at one point, pushed off its centre line with a twist: the reaction's
  // moment about the contact point is zero (a single point transmits a force only), and the
  // force lies inside the friction cone.
  Rig rig(Contact(0.3));
  PairSpec sphere = Floor({Vec3(0.03, 0.02, -kHalf)});
  sphere.key = 4;
  sphere.body = 7;
  sphere.is_static = false;
  sphere.p_BCm = Vec3(0.0, 0.0, -0.04);
  (void)rig.Tick({sphere}, Pressed());
  const Pose X_WP = Pressed(Vec3(3e-4, 0, -2e-4), About(Vec3::UnitZ(), 0.05));
  const ProxyOutput& out = rig.Tick({sphere}, X_WP);
  ASSERT_EQ(out.reactions.size(), 1u);
  const Wrench& r = out.reactions[0].w_W;
  const Vec3 contact = X_WP * Vec3(0.03, 0.02, -kHalf);
  const double normal = -r.f.z();
  ASSERT_GT(normal, 0.0);
  EXPECT_LT(MomentAbout(r, sphere.p_BCm, contact).norm(), 1e-9 * r.f.norm());
  EXPECT_LE(std::hypot(r.f.x(), r.f.y()), 0.3 * normal * (1.0 + 1e-9));
  // Under eq. 3.8 with a rotation weight other than k_r / k_t (here the T3.1 pointer's 3.33 m²)
  // the same push gives the sphere a couple about the contact.
  ProxyRendererSettings thesis = Contact(0.3);
  thesis.torque_model = ProxyTorqueModel::kThesis;
  thesis.rotation_weight = 3.33 * Mat3::Identity();
  Rig eq38(thesis);
  (void)eq38.Tick({sphere}, Pressed());
  const ProxyOutput& t = eq38.Tick({sphere}, X_WP);
  ASSERT_EQ(t.reactions.size(), 1u);
  EXPECT_GT(MomentAbout(t.reactions[0].w_W, sphere.p_BCm, contact).norm(), 1e-4);
}

TEST(ProxyContactModelTest, FaceOnTheFloorFeelsKtTimesDepthLikeTheThesisModel) {
  // Static contacts: both models solve the same proxy, so a pressed face feels k_t·depth up.
  Rig rig(Contact(0.0));
  const ProxyOutput& out = rig.Tick({Floor(BottomFace())}, Pressed());
  EXPECT_NEAR(out.w_W.f.z(), kKt * kDepth, kForceTol);
  EXPECT_LT(out.w_W.f.head<2>().norm(), kForceTol);
  EXPECT_LT(out.w_W.tau.norm(), kForceTol);
}

TEST(ProxyContactModelTest, LoadMovingBetweenCoplanarObjectsDoesNotShakeTheFeltForce) {
  // A face pressed kDepth into four moving boxes, one under each corner, whose tops are level
  // to within eps: the diagonal pairs take turns being eps higher. Four coplanar points make
  // the rows redundant (rank 3), so the split of the load among the boxes is not unique: each
  // tick the active set may carry it on either diagonal. The proxy itself moves by about eps,
  // so the felt force must stay within k_t eps plus the damper's d_t 2 eps / dt of k_t kDepth.
  ProxyRendererSettings settings = Contact(0.0);
  settings.d_t = 10.0;
  Rig rig(settings);
  constexpr double kEps = 1e-7;
  const std::vector<Vec3> corners = {Vec3(kHalf, kHalf, -kHalf), Vec3(-kHalf, kHalf, -kHalf),
                                     Vec3(-kHalf, -kHalf, -kHalf), Vec3(kHalf, -kHalf, -kHalf)};
  const auto specs = [&](int tick) {
    std::vector<PairSpec> boxes;
    for (int i = 0; i < 4; ++i) {
      const double lift = (i + tick) % 2 == 0 ? kEps : 0.0;
      PairSpec box = Box(5 + i, Pose{Vec3(0, 0, lift), Quat::Identity()});
      box.key = static_cast<std::uint64_t>(20 + i);
      box.points_P = {corners[static_cast<std::size_t>(i)]};
      boxes.push_back(box);
    }
    return boxes;
  };
  const double bound = kKt * kEps + settings.d_t * 2.0 * kEps / kDt;
  double worst = 0.0, share_jump = 0.0, previous_share = -1.0;
  for (int tick = 0; tick < 40; ++tick) {
    const ProxyOutput& out = rig.Tick(specs(tick), Pressed());
    ASSERT_EQ(out.reactions.size(), 4u);
    const double share = -out.reactions[0].w_W.f.z() / out.w_W.f.z();
    if (tick > 0) {  // the damper starts at rest
      worst = std::max(worst, std::abs(out.w_W.f.z() - kKt * kDepth));
      share_jump = std::max(share_jump, std::abs(share - previous_share));
    }
    previous_share = share;
  }
  EXPECT_LE(worst, bound) << "the felt force left k_t kDepth by " << worst << " N";
  // What makes the case: the first box's share of the load did jump between ticks.
  EXPECT_GT(share_jump, 0.1);
}

// The pointer squeezed between a box under it and a box pressing on its top face, tilted by
// `tilt` (rad) from facing it squarely: both are kDepth deep, so the proxy satisfies both rows
// only ~2 kDepth / tilt to the side, and the rows nearly contradict each other.
std::vector<PairSpec> Wedge(double tilt) {
  PairSpec below = Box(5, Pose{});
  PairSpec above = Box(6, Pose{});
  above.key = 10;
  above.n_B = Vec3(std::sin(tilt), 0.0, -std::cos(tilt));
  above.p_BC = Vec3(0.0, 0.0, 2.0 * kHalf - 2.0 * kDepth);
  above.p_BCm = Vec3(0.0, 0.0, 2.0 * kHalf + 0.05);
  above.points_P = {Vec3(kHalf, kHalf, kHalf), Vec3(-kHalf, kHalf, kHalf),
                    Vec3(-kHalf, -kHalf, kHalf), Vec3(kHalf, -kHalf, kHalf)};
  return {below, above};
}

TEST(ProxyContactModelTest, AWedgedProxyGivesNoPairMoreThanMaxPairForce) {
  // Unbounded, the nearly contradictory rows ask for forces far beyond the k_t·depth each box
  // presses with; bounded, every pair carries at most max_pair_force, the forces keep their
  // directions (one common factor) and the reactions still cancel the felt wrench.
  Rig free(Contact(0.0));
  const ProxyOutput& wild = free.Tick(Wedge(0.01), Pressed());
  ASSERT_EQ(wild.reactions.size(), 2u);
  double largest = 0.0;
  for (const ProxyPairReaction& r : wild.reactions) largest = std::max(largest, r.w_W.f.norm());
  ASSERT_GT(largest, 100.0 * kKt * kDepth);
  EXPECT_EQ(wild.diagnostics.status & kProxyStatusPairForceLimited, 0u);

  constexpr double kLimit = 20.0;  // N
  ProxyRendererSettings settings = Contact(0.0);
  settings.max_pair_force = kLimit;
  Rig bounded(settings);
  const ProxyOutput& out = bounded.Tick(Wedge(0.01), Pressed());
  ASSERT_EQ(out.reactions.size(), 2u);
  EXPECT_NE(out.diagnostics.status & kProxyStatusPairForceLimited, 0u);
  Vec3 sum = Vec3::Zero();
  for (std::size_t i = 0; i < out.reactions.size(); ++i) {
    const Vec3& f = out.reactions[i].w_W.f;
    EXPECT_LE(f.norm(), kLimit * (1.0 + 1e-12));
    EXPECT_NEAR(f.normalized().dot(wild.reactions[i].w_W.f.normalized()), 1.0, 1e-12);
    sum -= f;
  }
  EXPECT_NEAR(std::max(out.reactions[0].w_W.f.norm(), out.reactions[1].w_W.f.norm()), kLimit, 1e-9);
  EXPECT_LT((sum - out.w_W.f).norm(), 1e-9 * kLimit);
}

TEST(ProxyContactModelTest, APairBelowMaxPairForceIsUnchanged) {
  ProxyRendererSettings settings = Contact(kMu);
  settings.max_pair_force = 2.0 * kKt * kDepth;
  Rig bounded(settings);
  Rig free(Contact(kMu));
  const Pose X_WP = Pressed(Vec3(2e-4, 0, 0), About(Vec3::UnitZ(), 0.01));
  (void)bounded.Tick({Box(5, Pose{})}, Pressed());
  (void)free.Tick({Box(5, Pose{})}, Pressed());
  const ProxyOutput& a = bounded.Tick({Box(5, Pose{})}, X_WP);
  const ProxyOutput& b = free.Tick({Box(5, Pose{})}, X_WP);
  ASSERT_GT(a.w_W.f.norm(), 0.5 * kKt * kDepth);
  EXPECT_EQ(a.diagnostics.status & kProxyStatusPairForceLimited, 0u);
  EXPECT_EQ(a.w_W.f, b.w_W.f);
  EXPECT_EQ(a.w_W.tau, b.w_W.tau);
}

TEST(ProxyContactModelTest, SettingsRefuseARotationalDamper) {
  ProxyRendererSettings s = Contact(0.0);
  s.d_r = 0.1;
  EXPECT_THROW(s.Validate(), InvalidArgument);
  s.d_r = 0.0;
  s.k_r = 0.0;
  EXPECT_THROW(s.Validate(), InvalidArgument);
}

TEST(ProxyContactModelTest, SettingsRefuseANonPositiveMaxPairForce) {
  ProxyRendererSettings s = Contact(0.0);
  for (const double bad : {0.0, -1.0, std::nan("")}) {
    s.max_pair_force = bad;
    EXPECT_THROW(s.Validate(), InvalidArgument) << bad;
  }
}

}  // namespace
}  // namespace mrh::render
