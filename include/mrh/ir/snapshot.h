// SPDX-License-Identifier: Apache-2.0
// Intermediate representations exchanged between the physics and haptic threads (fixed capacity).
#pragma once

#include <cstdint>

#include "mrh/core/fixed_vector.h"
#include "mrh/core/spatial.h"

namespace mrh::ir {

/// Capacities of the exchanged structures. Overflow drops items and sets a Status bit.
inline constexpr std::size_t kMaxNeighborBodies = 64;
inline constexpr std::size_t kMaxPointContacts = 128;

/// Status bits carried by snapshots and reports.
enum StatusBits : std::uint32_t {
  kStatusOk = 0,
  kStatusBodiesFull = 1u << 0,    ///< more neighbor bodies than kMaxNeighborBodies
  kStatusContactsFull = 1u << 1,  ///< more contacts than kMaxPointContacts
  kStatusReportDropped = 1u << 2, ///< the haptic→physics ring was full
};

/// A neighbor body as the haptic thread sees it over one period: its pose before and after the
/// physics step that produced the snapshot (for interpolation) and its velocity after it.
struct BodyMotion {
  int body = -1;                ///< world body id
  Pose X_WB_prev;               ///< body pose at the start of the physics step
  Pose X_WB;                    ///< body pose at the end of the physics step
  Vec3 p_BCm = Vec3::Zero();    ///< centre of mass in the body frame (m)
  Twist V_WCm;                  ///< COM velocity at the end of the step (world frame)
  bool is_static = false;       ///< a static body takes no reaction
};

/// Adachi's plane + point IR for a 3-DOF pointer (SPEC §4.4): a plane fixed on the object through
/// its closest point, with a world normal pointing from the object toward the pointer.
struct PointContact {
  int motion = -1;              ///< index into PhysicsSnapshot::bodies
  int geom = -1;                ///< world geom id (for diagnostics)
  Vec3 p_BC = Vec3::Zero();     ///< plane point on the object, body frame (m)
  Vec3 n_W = Vec3::UnitZ();     ///< unit plane normal, object → pointer, world frame
  double distance = 0.0;        ///< signed pointer–object distance when built (m)
};

/// Everything physics step k hands to haptic period k+1 (SPEC §4.9). Immutable once published.
struct PhysicsSnapshot {
  std::int64_t step = -1;       ///< physics step index k; -1 before the first step
  double t = 0.0;               ///< simulation time at the end of the step (s)
  double physics_dt = 0.0;      ///< s
  FixedVector<BodyMotion, kMaxNeighborBodies> bodies;
  FixedVector<PointContact, kMaxPointContacts> contacts;
  std::uint32_t status = kStatusOk;
};

/// Reaction impulse a haptic period delivered to one body (world frame).
struct BodyImpulse {
  int body = -1;                ///< world body id
  Vec3 linear = Vec3::Zero();   ///< ∫ f dt (N·s)
  Vec3 angular = Vec3::Zero();  ///< ∫ (p − p_Cm) × f dt about the body's COM (N·m·s)
  Vec3 last_force = Vec3::Zero();  ///< reaction force at the period's last tick (N)
};

/// Everything haptic period k hands to physics step k+1 (SPEC §4.9).
struct HapticReport {
  std::int64_t period = -1;     ///< haptic period index
  std::int64_t ticks = 0;       ///< ticks in this period
  double t = 0.0;               ///< time of the period's last tick (s)
  Pose X_WP;                    ///< pointer pose at the last tick (world)
  Twist V_WP;                   ///< pointer velocity at the last tick (world)
  FixedVector<BodyImpulse, kMaxNeighborBodies> impulses;
  std::uint32_t status = kStatusOk;

  /// Adds a later report into this one: impulses summed per body, pointer and last forces
  /// taken from the later report. RT-safe.
  void MergeLater(const HapticReport& later) noexcept;
  /// Adds an impulse for `body` (creating its entry if needed). RT-safe.
  void AddImpulse(int body, const Vec3& linear, const Vec3& angular,
                  const Vec3& force) noexcept;
};

}  // namespace mrh::ir
