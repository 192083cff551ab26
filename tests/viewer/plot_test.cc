// SPDX-License-Identifier: Apache-2.0
// Tests of the plot history ring.
#include "viewer/plot.h"

#include <gtest/gtest.h>

namespace mrh::viewer::internal {
namespace {

TickSample Sample(double t, double fx) {
  TickSample s;
  s.t = t;
  s.displayed_W.f = Vec3(fx, 0.0, 0.0);
  s.displayed_W.tau = Vec3(0.0, 0.0, -fx);
  return s;
}

TEST(PlotHistoryTest, KeepsTheNewestPointsOldestFirst) {
  PlotHistory history(3);
  for (int i = 0; i < 5; ++i) history.Push(Sample(i, 10.0 * i));
  ASSERT_EQ(history.size(), 3u);
  EXPECT_EQ(history[0].t, 2.0);
  EXPECT_EQ(history[2].t, 4.0);
  EXPECT_EQ(history[2].f[0], 40.0f);
  EXPECT_EQ(history[2].tau[2], -40.0f);
}

TEST(PlotHistoryTest, HoldsFewerPointsUntilFull) {
  PlotHistory history(10);
  history.Push(Sample(1.0, 1.0));
  history.Push(Sample(2.0, 2.0));
  ASSERT_EQ(history.size(), 2u);
  EXPECT_EQ(history[0].t, 1.0);
  EXPECT_EQ(history[1].t, 2.0);
}

TEST(PlotHistoryTest, ClearEmptiesIt) {
  PlotHistory history(4);
  history.Push(Sample(1.0, 1.0));
  history.Clear();
  EXPECT_EQ(history.size(), 0u);
}

}  // namespace
}  // namespace mrh::viewer::internal
