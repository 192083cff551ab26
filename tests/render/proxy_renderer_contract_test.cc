// SPDX-License-Identifier: Apache-2.0
// Tests of the 6-DOF proxy renderer's contract: no allocation in a tick, bad input, iteration
// and row caps, the rotation weight and settings errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/render/proxy_renderer.h"
#include "proxy_rig.h"
#include "support/alloc_guard.h"

namespace mrh::render {
namespace {

using namespace proxy_rig;  // NOLINT(google-build-using-namespace): the test vocabulary

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

TEST(ProxyRendererTest, TickDoesNotAllocate) {
  ProxyRendererSettings settings = Friction(3.33 * Mat3::Identity());
  settings.max_iterations = 50;
  Rig rig(settings);
  std::vector<PairSpec> specs{Floor(BottomFace()), Box(5, Pose{})};
  mrh::testing::AllocGuard guard;
  for (int tick = 0; tick < 300; ++tick) {
    const double s = 1e-4 * tick;
    specs[1].X_WB.p.x() = -s;
    (void)rig.Tick(specs, Pressed(Vec3(s, 0, 0), About(Vec3::UnitZ(), s)));
  }
  EXPECT_EQ(guard.count(), 0);
}

TEST(ProxyRendererTest, NonFiniteInputGivesZeroWrenchAndTheBadInputBit) {
  Rig rig(T31());
  const std::vector<PairSpec> floor{Floor(BottomFace())};
  Pose bad = Pressed();
  bad.p.x() = NAN;
  EXPECT_EQ(rig.Tick(floor, bad).diagnostics.status, kProxyStatusBadInput);
  EXPECT_EQ(rig.out->w_W.f.norm(), 0.0);
  Fill(floor, Pressed(), rig.ir.get());
  rig.renderer.Tick(*rig.ir, Pressed(), 0.0, rig.out.get());
  EXPECT_EQ(rig.out->diagnostics.status, kProxyStatusBadInput);
  rig.ir->points[0].depth = INFINITY;
  rig.renderer.Tick(*rig.ir, Pressed(), kDt, rig.out.get());
  EXPECT_EQ(rig.out->diagnostics.status, kProxyStatusBadInput);
  EXPECT_EQ(rig.out->w_W.f.norm() + rig.out->w_W.tau.norm(), 0.0);
}

// The points are checked while the rows are built: every field of every point counts, also of
// points that do not penetrate (and so get no row).
TEST(ProxyRendererTest, AnyNonFinitePointValueIsBadInputEvenWithoutARowForThePoint) {
  for (const double bad :
       {static_cast<double>(NAN), static_cast<double>(INFINITY), -static_cast<double>(INFINITY)}) {
    for (int field = 0; field < 7; ++field) {
      for (const bool penetrating : {true, false}) {
        Rig rig(Friction());  // friction: p_PV is used too
        const std::vector<PairSpec> floor{Floor(BottomFace())};
        Fill(floor, Pressed(), rig.ir.get());
        rig.renderer.Tick(*rig.ir, Pressed(), kDt, rig.out.get());
        ASSERT_EQ(rig.out->diagnostics.status, kProxyStatusOk);
        TickPoint& point = rig.ir->points[rig.ir->points.size() - 1];
        if (!penetrating) point.depth = -1e-3;
        double* const values[7] = {&point.p_PV.x(), &point.p_PV.y(), &point.p_PV.z(),
                                   &point.v_W.x(),  &point.v_W.y(),  &point.v_W.z(),
                                   &point.depth};
        *values[field] = bad;
        rig.renderer.Tick(*rig.ir, Pressed(), kDt, rig.out.get());
        EXPECT_EQ(rig.out->diagnostics.status, kProxyStatusBadInput)
            << "value " << bad << " field " << field << " penetrating " << penetrating;
        EXPECT_EQ(rig.out->w_W.f.norm() + rig.out->w_W.tau.norm(), 0.0);
      }
    }
  }
}

TEST(ProxyRendererTest, IterationCapGivesFiniteOutputAndTheNotConvergedBit) {
  ProxyRendererSettings settings = T31();
  settings.max_iterations = 1;
  settings.tolerance = 0.0;
  Rig rig(settings);
  const ProxyOutput& out = rig.Tick({Floor(BottomFace())}, Pressed());
  EXPECT_EQ(out.diagnostics.iterations, 1);
  EXPECT_NE(out.diagnostics.status & kProxyStatusNotConverged, 0u);
  EXPECT_TRUE(IsFinite(out.w_W));
}

TEST(ProxyRendererTest, RowsBeyondCapacityAreDroppedWithTheRowsFullBit) {
  ProxyRendererSettings settings = T31();
  settings.max_rows = 2;
  Rig rig(settings);
  const ProxyOutput& out = rig.Tick({Floor(BottomFace())}, Pressed());
  EXPECT_EQ(out.diagnostics.rows, 2);
  EXPECT_NE(out.diagnostics.status & kProxyStatusRowsFull, 0u);
}

TEST(ProxyRendererTest, RotationWeightFromInertiaScalesTheUnitMassInertia) {
  // Thesis §3.4.1: a 0.2 m cube has 0.2²/6 m²; ×500 gives T3.1's R_w ≈ 3.33.
  const Mat3 weight = RotationWeightFromInertia((0.04 / 6.0) * Mat3::Identity(), 500.0);
  EXPECT_NEAR(weight(0, 0), 3.3333333333, 1e-9);
  EXPECT_EQ(weight(0, 1), 0.0);
}

TEST(ProxyRendererTest, RotationWeightFromInertiaRejectsBadInput) {
  EXPECT_THAT(
      [] {
        (void)RotationWeightFromInertia(Mat3::Identity(), 0.0);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("scale = 0")));
  EXPECT_THAT(
      [] {
        (void)RotationWeightFromInertia(-Mat3::Identity(), 1.0);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("symmetric positive definite tensor")));
}

void ExpectRejected(void (*edit)(ProxyRendererSettings*), const char* message) {
  ProxyRendererSettings settings;
  edit(&settings);
  EXPECT_THAT(
      [&] {
        ProxyRenderer renderer(settings);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr(message)));
}

TEST(ProxyRendererTest, SettingsErrorsNameTheFieldAndTheExpectedRange) {
  ExpectRejected(
      [](ProxyRendererSettings* s) {
        s->k_t = -1;
      },
      "k_t = -1 N/m; expected");
  ExpectRejected(
      [](ProxyRendererSettings* s) {
        s->d_t = NAN;
      },
      "d_t = nan");
  ExpectRejected(
      [](ProxyRendererSettings* s) {
        s->k_r = -2;
      },
      "k_r = -2 N·m/rad");
  ExpectRejected(
      [](ProxyRendererSettings* s) {
        s->d_r = -3;
      },
      "d_r = -3");
  ExpectRejected(
      [](ProxyRendererSettings* s) {
        s->mu = -0.1;
      },
      "mu = -0.1");
  ExpectRejected(
      [](ProxyRendererSettings* s) {
        s->tolerance = -1;
      },
      "tolerance = -1 m");
  ExpectRejected(
      [](ProxyRendererSettings* s) {
        s->rotation_weight(0, 1) = 0.5;
      },
      "rotation_weight = [1 0.5 0; 0 1 0; 0 0 1] m²; expected a finite symmetric");
  ExpectRejected(
      [](ProxyRendererSettings* s) {
        s->rotation_weight(2, 2) = 0;
      },
      "positive definite");
  ExpectRejected(
      [](ProxyRendererSettings* s) {
        s->max_iterations = 0;
      },
      "max_iterations = 0; expected 1..100000");
  ExpectRejected(
      [](ProxyRendererSettings* s) {
        s->max_rows = 0;
      },
      "max_rows = 0; expected 1..");
  ExpectRejected(
      [](ProxyRendererSettings* s) {
        s->max_rows = kMaxProxyRows + 1;
      },
      "max_rows = 4097");
}

}  // namespace
}  // namespace mrh::render
