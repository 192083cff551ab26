// SPDX-License-Identifier: Apache-2.0
// Tests of the contact-normal classification by nearest face: face–face, a vertex or edge on a
// face, a curved object's side on a face, a curved pointer.
#include "physics/normal_feature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace mrh::physics::internal {
namespace {

constexpr int kSegments = 16;

geometry::ConvexPolyhedron Box(double hx, double hy, double hz) {
  return geometry::ConvexPolyhedron::FromShape(
      geometry::Shape{geometry::ShapeType::kBox, Vec3(hx, hy, hz), nullptr}, kSegments);
}

geometry::ConvexPolyhedron Cylinder(double r, double h) {
  return geometry::ConvexPolyhedron::FromShape(
      geometry::Shape{geometry::ShapeType::kCylinder, Vec3(r, h, 0.0), nullptr}, kSegments);
}

geometry::ConvexPolyhedron Sphere(double r) {
  return geometry::ConvexPolyhedron::FromShape(
      geometry::Shape{geometry::ShapeType::kSphere, Vec3(r, 0.0, 0.0), nullptr}, kSegments);
}

Pose Yawed(double yaw, const Vec3& p) {
  return Pose{p, Quat(Eigen::AngleAxisd(yaw, Vec3::UnitZ()))};
}

// A box pointer at the origin pushes along +x an object ahead of it: the pointer's +x face
// meets it, and the contact normal (object → pointer) is about −x.
const Pose kPointerPose = Yawed(0.0, Vec3::Zero());
const Vec3 kPointerFaceNormal = -Vec3::UnitX();  // object → pointer, the pointer's +x face

TEST(NormalFeature, FaceOnFaceNearlyParallelIsTheObjectsFaceAtEitherMinimalDirection) {
  const geometry::ConvexPolyhedron pointer = Box(0.01, 0.03, 0.02);
  const geometry::ConvexPolyhedron object = Box(0.03, 0.05, 0.02);
  const double tilt = 0.02;  // rad, the object yawed against the pointer face
  const Pose X_WO = Yawed(tilt, Vec3(0.038, 0.0, 0.0));  // 2 mm into the pointer's face
  const Vec3 object_face = X_WO.q * -Vec3::UnitX();
  // The pointer face's corners, all in the object: the region's vertices on the pointer.
  const std::vector<Vec3> corners = {Vec3(0.01, 0.03, 0.02), Vec3(0.01, -0.03, 0.02),
                                     Vec3(0.01, 0.03, -0.02), Vec3(0.01, -0.03, -0.02)};
  // EPA may return either face's normal; both name the object's face.
  for (const Vec3& n : {kPointerFaceNormal, object_face}) {
    const NormalOwner owner = NormalFeature({&pointer, kPointerPose, Faces::kFlat},
                                            {&object, X_WO, Faces::kFlat}, n, corners);
    EXPECT_EQ(owner.frame, ir::NormalFrame::kObject);
    EXPECT_NEAR((owner.n_W - object_face).norm(), 0.0, 1e-12);
  }
}

// Two boxes side by side in y make one flat face toward the pointer (a compound body); the
// pointer's face spans the seam. The region of the pointer and the −y box has vertices on the
// seam face, where the box ends but the body's face goes on: the pair is still face on face.
TEST(NormalFeature, APatchEndingAtACompoundsSeamIsTheObjectsFace) {
  const geometry::ConvexPolyhedron pointer = Box(0.01, 0.03, 0.02);
  const geometry::ConvexPolyhedron half = Box(0.03, 0.025, 0.02);
  const double tilt = 0.02;
  const Pose X_WB = Yawed(tilt, Vec3(0.038, 0.0, 0.0));  // the body, 2 mm into the pointer
  const Pose X_WO = X_WB * Pose{Vec3(0.0, -0.025, 0.0), Quat::Identity()};
  const Vec3 seam_W = X_WB * Vec3(-0.0285, 0.0, 0.0);  // on the seam, in the pointer
  // The region's vertices: the pointer face's −y corners and the seam face's points on it.
  const std::vector<Vec3> points = {Vec3(0.01, -0.03, 0.02), Vec3(0.01, -0.03, -0.02),
                                    Vec3(0.01, seam_W.y(), 0.02), Vec3(0.01, seam_W.y(), -0.02)};
  const Vec3 object_face = X_WO.q * -Vec3::UnitX();
  for (const Vec3& n : {kPointerFaceNormal, object_face}) {
    const NormalOwner owner = NormalFeature({&pointer, kPointerPose, Faces::kFlat},
                                            {&half, X_WO, Faces::kFlat}, n, points);
    EXPECT_EQ(owner.frame, ir::NormalFrame::kObject);
    EXPECT_NEAR((owner.n_W - object_face).norm(), 0.0, 1e-12);
  }
}

TEST(NormalFeature, AnObjectEdgeOnAPointerFaceIsThePointersFace) {
  const geometry::ConvexPolyhedron pointer = Box(0.01, 0.03, 0.02);
  const geometry::ConvexPolyhedron object = Box(0.03, 0.03, 0.02);
  // Yawed about 45°: a vertical edge of the object faces the pointer, 2 mm into its face; the
  // object's faces beside it are 40° and 50° off the pointer's.
  const Pose yawed = Yawed(std::numbers::pi / 4.0 + 0.09, Vec3::Zero());
  Vec3 edge = Vec3::Constant(1.0);
  for (const Vec3& v : object.vertices()) {
    if ((yawed * v).x() < edge.x()) edge = yawed * v;
  }
  const Pose X_WO = Yawed(std::numbers::pi / 4.0 + 0.09, Vec3(0.008 - edge.x(), 0.0, 0.0));
  const double y_edge = edge.y();
  // Region vertices on the pointer's face either side of the edge, each under one of its faces.
  const std::vector<Vec3> points = {Vec3(0.01, y_edge + 0.001, 0.01),
                                    Vec3(0.01, y_edge - 0.001, 0.01)};
  for (const Vec3& p : points) {
    for (const geometry::Halfspace& h : object.faces()) {
      ASSERT_LT(h.a.dot(X_WO.Inverse() * p), h.b) << "the point lies in the object";
    }
  }
  const NormalOwner owner =
      NormalFeature({&pointer, kPointerPose, Faces::kFlat}, {&object, X_WO, Faces::kFlat},
                    kPointerFaceNormal, points);
  EXPECT_EQ(owner.frame, ir::NormalFrame::kPointer);
  EXPECT_NEAR((owner.n_W - kPointerFaceNormal).norm(), 0.0, 1e-12);
}

TEST(NormalFeature, ACylindersSideOnAPointerFaceIsThePointersFaceAtAnyTurnOfTheCylinder) {
  const geometry::ConvexPolyhedron pointer = Box(0.01, 0.03, 0.02);
  const geometry::ConvexPolyhedron object = Cylinder(0.04, 0.04);
  // At one turn a facet of the tessellated side faces the pointer exactly, at another an edge
  // between two facets does: the cylinder's side is the same surface at both.
  for (const double yaw : {0.0, std::numbers::pi / kSegments, 0.1}) {
    const Pose X_WO = Yawed(yaw, Vec3(0.05, 0.0, 0.0));
    const NormalOwner owner = NormalFeature({&pointer, kPointerPose, Faces::kFlat},
                                            {&object, X_WO, Faces::kAxial}, kPointerFaceNormal, {});
    EXPECT_EQ(owner.frame, ir::NormalFrame::kPointer) << "yaw " << yaw;
    EXPECT_NEAR((owner.n_W - kPointerFaceNormal).norm(), 0.0, 1e-12);
  }
}

TEST(NormalFeature, AnEllipsoidOnAPointerFaceKeepsItsNormalOnTheObject) {
  const geometry::ConvexPolyhedron pointer = Box(0.01, 0.03, 0.02);
  const geometry::ConvexPolyhedron object = geometry::ConvexPolyhedron::FromShape(
      geometry::Shape{geometry::ShapeType::kEllipsoid, Vec3(0.05, 0.03, 0.03), nullptr}, kSegments);
  const Pose X_WO = Yawed(0.1, Vec3(0.06, 0.0, 0.0));
  const NormalOwner owner = NormalFeature({&pointer, kPointerPose, Faces::kFlat},
                                          {&object, X_WO, Faces::kCurved}, kPointerFaceNormal, {});
  EXPECT_EQ(owner.frame, ir::NormalFrame::kObject);
  EXPECT_NEAR((owner.n_W - kPointerFaceNormal).norm(), 0.0, 1e-12);
}

TEST(NormalFeature, APointerEdgeOnAnObjectFaceIsTheObjectsFace) {
  const geometry::ConvexPolyhedron pointer = Box(0.01, 0.03, 0.02);
  const geometry::ConvexPolyhedron object = Box(0.05, 0.05, 0.02);
  // The pointer yawed 45° touches the object's −x face with a vertical edge.
  const Pose X_WP = Yawed(std::numbers::pi / 4.0, Vec3::Zero());
  const Pose X_WO = Yawed(0.0, Vec3(0.07, 0.0, 0.0));
  const Vec3 n = -Vec3::UnitX();
  const NormalOwner owner =
      NormalFeature({&pointer, X_WP, Faces::kFlat}, {&object, X_WO, Faces::kFlat}, n, {});
  EXPECT_EQ(owner.frame, ir::NormalFrame::kObject);
  EXPECT_NEAR((owner.n_W - n).norm(), 0.0, 1e-12);
}

TEST(NormalFeature, ACurvedPointerNamesNoFeatureRoundAnEdge) {
  const geometry::ConvexPolyhedron pointer = Sphere(0.015);
  const geometry::ConvexPolyhedron object = Box(0.03, 0.03, 0.02);
  const Pose X_WO = Yawed(0.0, Vec3(0.05, 0.0, 0.0));
  // Round the object's vertical edge: the normal lies between its two faces and stays as given.
  const Vec3 n = Vec3(-1.0, -0.2, 0.0).normalized();
  const NormalOwner owner =
      NormalFeature({&pointer, kPointerPose, Faces::kCurved}, {&object, X_WO, Faces::kFlat}, n, {});
  EXPECT_EQ(owner.frame, ir::NormalFrame::kObject);
  EXPECT_NEAR((owner.n_W - n).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace mrh::physics::internal
