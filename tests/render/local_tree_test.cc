// SPDX-License-Identifier: Apache-2.0
// Joint space in the contact local model (render/local_tree.cc): which trees the solver takes
// into joint coordinates, and a sprung slide against its closed-form oscillation.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "mrh/render/local_contact_solver.h"

namespace mrh::render {
namespace {

constexpr double kDt = 0.001;

ir::LocalIslandBody Body(double x, double mass = 0.1) {
  ir::LocalIslandBody b;
  b.body = static_cast<int>(x * 100.0) + 1;
  b.mass = mass;
  b.inertia_B = Mat3::Identity() * 1e-4;
  b.X_WB = Pose{Vec3(x, 0, 1), Quat::Identity()};
  return b;
}

// Joint of body `child` to `parent` (-1: the world) at the child's origin, about / along y.
ir::LocalJoint Joint(ir::LocalJointType type, int child, int parent, const Pose& X_PJ) {
  ir::LocalJoint j;
  j.type = type;
  j.child = child;
  j.parent = parent;
  j.joint = child;
  j.X_PJ = X_PJ;
  j.axis = Vec3::UnitY();
  return j;
}

// A chain of `n` bodies 0.1 m apart, the first jointed to the world, joint k of type types(k).
template <typename Types>
ir::LocalContactModel Chain(int n, Types types) {
  ir::LocalContactModel m;
  m.valid = true;
  for (int i = 0; i < n; ++i) {
    EXPECT_TRUE(m.bodies.PushBack(Body(0.1 * i)));
    const Pose X_PJ = i == 0 ? m.bodies[0].X_WB : Pose{Vec3(0.1, 0, 0), Quat::Identity()};
    EXPECT_TRUE(m.joints.PushBack(Joint(types(i), i, i - 1, X_PJ)));
  }
  return m;
}

std::size_t TreeDofs(const ir::LocalContactModel& m) {
  auto solver = std::make_unique<LocalContactSolver>();
  solver->Adopt(m);
  EXPECT_EQ(solver->joint_count(), m.joints.size());
  return solver->tree_dof_count();
}

TEST(LocalTreeTest, WorldRootedHingeSlideAndWeldTreesFitUpToTheCapacity) {
  const auto hinges = [](int) {
    return ir::LocalJointType::kHinge;
  };
  const auto mixed = [](int i) {
    return i == 2   ? ir::LocalJointType::kSlide
           : i == 3 ? ir::LocalJointType::kWeld
                    : ir::LocalJointType::kHinge;
  };
  EXPECT_EQ(TreeDofs(Chain(6, mixed)), 5u);  // the weld has no coordinate
  EXPECT_EQ(TreeDofs(Chain(LocalContactSolver::kMaxTreeDofs, hinges)),
            LocalContactSolver::kMaxTreeDofs);
  // One past the capacity: the whole tree keeps its rows, not a part of it.
  EXPECT_EQ(TreeDofs(Chain(LocalContactSolver::kMaxTreeDofs + 1, hinges)), 0u);
}

TEST(LocalTreeTest, BallJointsAndTreesOnAFreeBodyKeepTheirRows) {
  const auto ball_third = [](int i) {
    return i == 2 ? ir::LocalJointType::kBall : ir::LocalJointType::kHinge;
  };
  EXPECT_EQ(TreeDofs(Chain(4, ball_third)), 0u);
  // A lid hinged to a free box: the tree's root moves on its own.
  ir::LocalContactModel m;
  m.valid = true;
  EXPECT_TRUE(m.bodies.PushBack(Body(0.0, 1.0)));
  EXPECT_TRUE(m.bodies.PushBack(Body(0.1)));
  EXPECT_TRUE(m.joints.PushBack(Joint(ir::LocalJointType::kHinge, 1, 0, Pose{Vec3(0.1, 0, 0)})));
  EXPECT_EQ(TreeDofs(m), 0u);
}

// A 0.1 kg body on a slide with a spring (k 10 N/m) and armature a: it oscillates at
// ω = sqrt(k / (m + a)), both without and with armature. Semi-implicit Euler at 1 ms shifts the
// period by (ω Δt)² / 24, under 1e-5 here.
TEST(LocalTreeTest, SprungSlideOscillatesAtItsNaturalFrequency) {
  for (const double armature : {0.0, 0.1}) {
    ir::LocalContactModel m = Chain(1, [](int) {
      return ir::LocalJointType::kSlide;
    });
    m.joints[0].stiffness = 10.0;
    m.joints[0].armature = armature;
    m.bodies[0].X_WB.p.y() += 0.01;  // 1 cm from the spring's rest
    auto solver = std::make_unique<LocalContactSolver>();
    solver->Adopt(m);
    ASSERT_EQ(solver->tree_dof_count(), 1u);
    double previous = solver->JointPosition(0), first = -1.0, last = -1.0;
    int crossings = 0;
    for (int k = 1; k <= 5000; ++k) {
      ASSERT_TRUE(solver->Step(kDt));
      const double q = solver->JointPosition(0);
      if (previous > 0.0 && q <= 0.0) {  // downward zero crossing, interpolated
        const double t = (k - 1 + previous / (previous - q)) * kDt;
        if (first < 0.0) first = t;
        last = t;
        ++crossings;
      }
      previous = q;
    }
    ASSERT_GE(crossings, 3);
    const double period = (last - first) / (crossings - 1);
    const double expected = 2.0 * std::numbers::pi * std::sqrt((0.1 + armature) / 10.0);
    EXPECT_NEAR(period, expected, 1e-4 * expected) << "armature " << armature;
  }
}

}  // namespace
}  // namespace mrh::render
