// SPDX-License-Identifier: Apache-2.0
// Experiment t3.7's cases, variants and bars, shared by its runs (t3_7.cc) and its report
// (t3_7_report.cc).
#pragma once

#include <fmt/format.h>

#include <numbers>
#include <string>
#include <vector>

#include "experiment_util.h"
#include "experiments_impl.h"

namespace mrh::experiments::internal {

inline constexpr double kSpeed = 0.1;     // m/s along +x
inline constexpr double kTouch = 1.0;     // s, the pointer reaches the object
inline constexpr double kDuration = 5.0;  // s
inline constexpr double kFrom = 2.0;      // s, statistics window 2–5 s
inline constexpr double kFriction = 0.5;  // the floor's (scenes/t3_7_*.xml); pointers have none
inline constexpr double kThrowBar = 2.5;  // the acceptance bar: speed ≤ 2.5 v, spin ≤ 2.5 v / r
inline constexpr double kSlideBar = 0.05;  // steady slide: mean |f| within 5 % of μ m g
inline constexpr double kForceBar = 0.10;  // off-centre: mean |f| within 10 % of the reference's
inline constexpr double kPoseBar = 0.02;  // m, off-centre: positions within 2 cm of the reference's
// A turn smaller than this in the reference has no direction worth comparing.
inline constexpr double kTurnFloor = 5.0 * std::numbers::pi / 180.0;

// Rendering gains shared by every method; the virtual coupling's are matched to them.
inline constexpr double kStiffness = 2000.0;   // N/m
inline constexpr double kDamping = 5.0;        // N·s/m
inline constexpr double kRotStiffness = 20.0;  // N·m/rad
// The coupled tool: the pointers weigh 14 and 48 g; 0.1 kg and 1e-3 kg·m² keep the coupling
// stable at these gains (the rotation needs the inertia) and damped enough not to ring.
inline constexpr double kToolMass = 0.1;       // kg
inline constexpr double kToolInertia = 0.001;  // kg·m², each principal moment

enum class Motion { kRolls, kSlides };

struct Shape {
  const char* name;
  double reach;   // m, from the object's centre to its surface toward −x
  double push_z;  // m, pointer height
  Motion motion;
  // m, rolling radius (kRolls): the smallest a rolling body turns on, so v / r bounds its spin.
  double radius;
  // Its side is round about a vertical axis: every contact normal there passes through the
  // axis, so a centred point push cannot turn it.
  bool round_side;
};

// The ellipsoid, pushed at its long end, tips onto it and rolls like an egg: its centre falls
// from 5 to 3 cm each half turn, so gravity, not the push, sets its speed (√(2 g 0.02) = 0.63 m/s).
inline constexpr Shape kShapes[] = {{"sphere", 0.04, 0.04, Motion::kRolls, 0.04, true},
                                    {"capsule", 0.03, 0.03, Motion::kRolls, 0.03, false},
                                    {"cylinder", 0.04, 0.04, Motion::kSlides, 0.0, true},
                                    {"ellipsoid", 0.05, 0.03, Motion::kRolls, 0.03, false},
                                    {"mesh", 0.034641, 0.03, Motion::kSlides, 0.0, false},
                                    {"compound", 0.03, 0.03, Motion::kSlides, 0.0, false}};

struct PointerKind {
  const char* name;  // "box" | "sphere"
  const char* body;  // mocap body in every t3.7 scene
  double reach;      // m, from the pointer's origin to its face toward +x
  // m along +y, the off-centre push: the box pointer's face (6 cm wide) then lies wholly on one
  // side of the objects' centre line, so its centre of pressure is off centre.
  double offset;
  // A flat face: pressed square on an object's flat side it holds it straight (the centre of
  // pressure moves to resist a turn), where a point push on a flat side is an unstable
  // equilibrium that turns the object one way or the other.
  bool face;
};

inline constexpr PointerKind kPointers[] = {{"box", "box_pointer", 0.01, 0.04, true},
                                            {"sphere", "sphere_pointer", 0.015, 0.02, false}};

struct Variant {
  const char* label;
  const char* method;
  double physics_dt;
};

inline constexpr Variant kVariants[] = {{"virtual-coupling@1ms", "virtual-coupling", 0.001},
                                        {"proxy-6dof@1ms", "proxy-6dof", 0.001},
                                        {"proxy-6dof@20ms", "proxy-6dof", 0.02},
                                        {"local-dynamics-6dof@20ms", "local-dynamics-6dof", 0.02}};

struct Case {
  const Shape* shape;
  const PointerKind* pointer;
  double y;  // m, pointer offset

  std::string Name() const {
    return fmt::format("{}_{}_{}", shape->name, pointer->name, y == 0.0 ? "centred" : "offcentre");
  }
};

/// A run's name in file names: case and variant.
inline std::string RunSlug(const Case& c, const Variant& v) {
  return c.Name() + "_" + Slug(v.label, '_');
}

/// The cases `options` selects, in run order.
std::vector<Case> Cases(const T37Options& options);

}  // namespace mrh::experiments::internal
