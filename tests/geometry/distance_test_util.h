// SPDX-License-Identifier: Apache-2.0
// Shape and pose builders shared by the geometry tests.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>

#include "mrh/geometry/distance.h"

namespace mrh::geometry::testing {

inline Shape MakeShape(ShapeType type, const Vec3& size) {
  Shape shape;
  shape.type = type;
  shape.size = size;
  return shape;
}

inline Shape SphereShape(double r) {
  return MakeShape(ShapeType::kSphere, Vec3(r, 0, 0));
}

inline Shape BoxShape(double hx, double hy, double hz) {
  return MakeShape(ShapeType::kBox, Vec3(hx, hy, hz));
}

inline Shape CapsuleShape(double r, double half_length) {
  return MakeShape(ShapeType::kCapsule, Vec3(r, half_length, 0));
}

inline Shape CylinderShape(double r, double half_height) {
  return MakeShape(ShapeType::kCylinder, Vec3(r, half_height, 0));
}

inline Shape EllipsoidShape(double rx, double ry, double rz) {
  return MakeShape(ShapeType::kEllipsoid, Vec3(rx, ry, rz));
}

inline Shape PlaneShape() {
  return MakeShape(ShapeType::kPlane, Vec3::Zero());
}

/// The box [-hx, hx] x [-hy, hy] x [-hz, hz] as an outward-wound triangle mesh.
inline Shape BoxMeshShape(double hx, double hy, double hz) {
  auto mesh = std::make_shared<ConvexMesh>();
  for (int i = 0; i < 8; ++i) {
    mesh->vertices.emplace_back((i & 1) ? hx : -hx, (i & 2) ? hy : -hy, (i & 4) ? hz : -hz);
  }
  // Two triangles per face, counter-clockwise seen from outside.
  mesh->triangles = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                     {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  Shape shape;
  shape.type = ShapeType::kMesh;
  shape.mesh = std::move(mesh);
  return shape;
}

inline Pose At(double x, double y, double z, const Quat& q = Quat::Identity()) {
  return Pose{Vec3(x, y, z), q};
}

/// A rotation about a generic axis, so that no test depends on axis alignment.
inline Quat GenericRotation() {
  return Quat(Eigen::AngleAxisd(0.7, Vec3(1.0, -2.0, 0.5).normalized()));
}

MATCHER_P2(IsNear, expected, tolerance, "") {
  const double error = (arg - expected).norm();
  *result_listener << "is " << arg.transpose() << ", error " << error;
  return error <= tolerance;
}

}  // namespace mrh::geometry::testing
