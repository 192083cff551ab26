// SPDX-License-Identifier: Apache-2.0
// Haptic half of baselines B1 and B4: 3-DOF penalty rendering, reaction summed into impulses.
#pragma once

#include <array>

#include "mrh/haptic/method_haptic.h"
#include "mrh/render/contact_transients.h"
#include "mrh/render/point_friction.h"
#include "normal_carry.h"

namespace mrh::haptic::internal {

/// The haptic half of B1/B4: renders corrected eq. 4.11 against object poses blended from one
/// step behind to the newest (α = min(1, (j+1)/n)), normals blended likewise, and sums the
/// reaction −f_d into per-body impulses for EndPeriod. Its physics half is
/// physics::internal::PointPenaltyPhysics.
class PointPenaltyHaptic final : public MethodHaptic {
 public:
  /// radius (m), stiffness k (N/m), damping d (N·s/m) of eq. 4.11; friction μ (>= 0):
  /// 0 renders no friction at all (whatever the materials say), > 0 a Coulomb cone per contact
  /// through a stick anchor (render::RenderPointFriction), μ from the geom's material if it has
  /// one, else `friction`, with the contact's normal stiffness as the tangential spring.
  PointPenaltyHaptic(double radius, double stiffness, double damping, double friction = 0.0)
      : radius_(radius), stiffness_(stiffness), damping_(damping), friction_(friction) {}

  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override;
  void HapticTick(const TickInput& in, TickOutput* out) noexcept override;
  void EndPeriod(ir::HapticReport* report) noexcept override;

 private:
  void RenderContact(std::size_t i, const TickInput& in, double alpha, TickOutput* out) noexcept;

  double radius_;
  double stiffness_;
  double damping_;
  double friction_;
  render::PointFrictionAnchors<ir::kMaxPointContacts> anchors_;
  ir::PhysicsSnapshot snapshot_;
  ContactNormals previous_n_{};
  ContactNormals rendered_n_{};
  std::array<Vec3, ir::kMaxNeighborBodies> tick_force_{};
  std::array<Vec3, ir::kMaxNeighborBodies> tick_torque_{};
  ir::HapticReport period_;
  // Material vibration at contact onset, added to the rendered force.
  render::ContactTransients transients_;
};

}  // namespace mrh::haptic::internal
