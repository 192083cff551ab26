// SPDX-License-Identifier: Apache-2.0
// Intermediate representations exchanged between the physics and haptic threads (fixed capacity).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "mrh/core/fixed_vector.h"
#include "mrh/core/spatial.h"
#include "mrh/ir/local_contact.h"
#include "mrh/ir/material.h"

namespace mrh::ir {

/// Capacities of the exchanged structures. Overflow drops items and sets a Status bit.
inline constexpr std::size_t kMaxNeighborBodies = 128;
inline constexpr std::size_t kMaxPointContacts = 256;
/// Pointer-geom/object-geom pairs of the geometric IR (6-DOF, thesis §3.2.1).
inline constexpr std::size_t kMaxGeometricPairs = 64;
/// Contact points over all geometric pairs (an N-gon prism face gives N; T3.4 goes to 1000).
inline constexpr std::size_t kMaxPairPoints = 2048;

using Mat63 = Eigen::Matrix<double, 6, 3>;

/// Status bits carried by snapshots and reports.
enum StatusBits : std::uint32_t {
  kStatusOk = 0,
  kStatusBodiesFull = 1u << 0,      ///< more neighbor bodies than kMaxNeighborBodies
  kStatusContactsFull = 1u << 1,    ///< more contacts than kMaxPointContacts
  kStatusReportDropped = 1u << 2,   ///< the haptic→physics ring was full
  kStatusPairsFull = 1u << 3,       ///< more geometric pairs than kMaxGeometricPairs
  kStatusPointsFull = 1u << 4,      ///< more contact points than kMaxPairPoints
  kStatusRegionFallback = 1u << 5,  ///< a penetration region failed; closest point sent instead
};

/// A neighbor body as the haptic thread sees it over one period: its pose before and after the
/// physics step that produced the snapshot (for interpolation) and its velocity after it.
struct BodyMotion {
  int body = -1;              ///< world body id
  Pose X_WB_prev;             ///< body pose at the start of the physics step
  Pose X_WB;                  ///< body pose at the end of the physics step
  Vec3 p_BCm = Vec3::Zero();  ///< centre of mass in the body frame (m)
  Twist V_WCm;                ///< COM velocity at the end of the step (world frame)
  bool is_static = false;     ///< a static body takes no reaction

  // Dynamic IR (method local-dynamics, thesis §4.2.2, §4.4.2); unused by the other methods.
  bool has_dynamics = false;  ///< A, b and dV_n below are valid
  /// Accelerance A (eq. 4.10): COM acceleration (linear rows 0–2, m/s² per N; angular rows 3–5,
  /// rad/s² per N) per unit force applied at the contact point p_BA, world frame.
  Mat63 A = Mat63::Zero();
  Vec6 b = Vec6::Zero();     ///< bias acceleration (linear; angular), world frame
  Vec3 p_BA = Vec3::Zero();  ///< point where the test forces acted, body frame (m)
  /// Velocity correction of eq. 4.18 (third term, already × Δt^G), added once at tick j = 0.
  Twist dV_n;
  /// True when the body was a neighbor in the previous step too (its local state continues);
  /// false: the local simulation starts from X_WB / V_WCm.
  bool continues = false;
};

/// Adachi's plane + point IR for a 3-DOF pointer (thesis §4.2.1): a plane fixed on the object
/// through its closest point, with a world normal pointing from the object toward the pointer.
struct PointContact {
  int motion = -1;           ///< index into PhysicsSnapshot::bodies
  int geom = -1;             ///< world geom id (for diagnostics)
  Vec3 p_BC = Vec3::Zero();  ///< plane point on the object, body frame (m)
  Vec3 n_W = Vec3::UnitZ();  ///< unit plane normal, object → pointer, world frame
  double distance = 0.0;     ///< signed pointer–object distance when built (m)
  /// Round objects: r > 0 when the object's geom is a sphere or a capsule, whose surface is the
  /// points within r of the segment core_B[0]–core_B[1] (body frame; one point for a sphere). A
  /// local simulation that turns the body re-derives the plane each tick from the core point
  /// nearest the pointer: a plane fixed on a rolling body turns with it, and a force along its
  /// turned normal would drive the roll.
  double r = 0.0;
  std::array<Vec3, 2> core_B{Vec3::Zero(), Vec3::Zero()};
  ContactMaterial material;  ///< the geom's haptic material (none: rendering.*)
};

/// One pointer-geom/object-geom pair of the geometric IR (thesis §3.2.1): a plane fixed on the
/// object and the pointer's contact points below it.
/// The body a geometric pair's contact normal belongs to (its face, or the face a feature of the
/// other body lies on): the normal turns with that body while the other moves relative to it.
enum class NormalFrame : std::uint8_t {
  kObject,   ///< an object face (or an edge–edge contact, or any contact of a curved pointer)
  kPointer,  ///< a pointer face: an object edge or vertex, or a curved object's side, on it
};

struct GeometricPair {
  int motion = -1;           ///< index into PhysicsSnapshot::bodies (the object's body)
  int object_geom = -1;      ///< world geom id of the object side
  int pointer_geom = -1;     ///< world geom id of the pointer side
  Vec3 n_W = Vec3::UnitZ();  ///< unit plane normal at the end of the step, object → pointer
  Vec3 p_BC = Vec3::Zero();  ///< plane point c (object witness), object body frame (m)
  int first_point = 0;       ///< first index into PhysicsSnapshot::points
  int num_points = 0;        ///< number of contact points of this pair
  double distance = 0.0;     ///< signed pointer–object distance when built (m)
  /// true: points are penetration-region vertices below the plane; false: the fallback (not
  /// penetrating, touching, or region failed): the pointer-side closest point only.
  bool penetrating = false;
  /// The object's geom is a sphere or a capsule: where it rolls (a capsule about its axis) its
  /// surface, and so the plane facing the pointer, does not turn with the body. An ellipsoid's
  /// does.
  bool round = false;
  /// The body whose face the contact normal is (physics::internal::NormalFeature) and the unit
  /// normal in that body's frame: the object body frame (a flat object's face normal exactly) or
  /// the pointer body frame. Read by the methods that move the object during the period
  /// (local-dynamics-6dof); n_W is the minimal penetration direction, as built. Zero (a pair
  /// made without the builder): n_W, held in the object's frame.
  NormalFrame normal_frame = NormalFrame::kObject;
  Vec3 n_F = Vec3::Zero();
  ContactMaterial material;  ///< the object geom's haptic material (none: rendering.*)
};

/// A contact point of a geometric pair, fixed on the pointer.
struct PairPoint {
  Vec3 p_PV = Vec3::Zero();  ///< position in the pointer body frame (m)
  double depth = 0.0;        ///< depth below the pair's plane when built (m, >= 0 if below)
};

/// The local-simulation state of a neighbor at the end of a haptic period (eq. 4.16–4.17).
struct LocalBodyState {
  int body = -1;  ///< world body id
  Pose X_WB;      ///< body pose
  Twist V_WCm;    ///< COM velocity, world frame
};

/// Everything physics step k hands to haptic period k+1 (the timing rule in
/// docs/architecture.md). Immutable once published.
struct PhysicsSnapshot {
  std::int64_t step = -1;   ///< physics step index k; -1 before the first step
  double t = 0.0;           ///< simulation time at the end of the step (s)
  double physics_dt = 0.0;  ///< s
  FixedVector<BodyMotion, kMaxNeighborBodies> bodies;
  FixedVector<PointContact, kMaxPointContacts> contacts;
  FixedVector<GeometricPair, kMaxGeometricPairs> pairs;
  FixedVector<PairPoint, kMaxPairPoints> points;
  /// The contact local model (local-dynamics with rendering.local_model "contact").
  LocalContactModel local_model;
  /// contact-volume (B2): the penalty wrench the scene exerts on the pointer during the step
  /// (world frame, torque about the pointer origin) and its number of penetrating pairs; zero
  /// for the other methods.
  Wrench pointer_wrench_W;
  int pointer_contacts = 0;
  std::uint32_t status = kStatusOk;
};

/// Reaction impulse a haptic period delivered to one body (world frame).
struct BodyImpulse {
  int body = -1;                   ///< world body id
  Vec3 linear = Vec3::Zero();      ///< ∫ f dt (N·s)
  Vec3 angular = Vec3::Zero();     ///< ∫ (p − p_Cm) × f dt about the body's COM (N·m·s)
  Vec3 last_force = Vec3::Zero();  ///< reaction force at the period's last tick (N)
};

/// Everything haptic period k hands to physics step k+1 (the timing rule in docs/architecture.md).
struct HapticReport {
  std::int64_t period = -1;  ///< haptic period index
  std::int64_t ticks = 0;    ///< ticks in this period
  double t = 0.0;            ///< time of the period's last tick (s)
  Pose X_WP;                 ///< pointer pose at the last tick (world)
  Twist V_WP;                ///< pointer velocity at the last tick (world)
  FixedVector<BodyImpulse, kMaxNeighborBodies> impulses;
  /// Local-simulation states at the period's last tick (local-dynamics only).
  FixedVector<LocalBodyState, kMaxNeighborBodies> local_states;
  std::uint32_t status = kStatusOk;

  /// Adds a later report into this one: impulses summed per body, pointer, last forces and
  /// local states taken from the later report (a body's newer state replaces its older one).
  /// RT-safe.
  void MergeLater(const HapticReport& later) noexcept;
  /// Adds an impulse for `body` (creating its entry if needed). RT-safe.
  void AddImpulse(int body, const Vec3& linear, const Vec3& angular, const Vec3& force) noexcept;
};

}  // namespace mrh::ir
