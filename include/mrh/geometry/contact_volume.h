// SPDX-License-Identifier: Apache-2.0
// The intersection polyhedron of a convex pair and its pressure integrals (contact-volume
// penalty, B2: Hasegawa & Sato 2004, thesis ref. [1], §1.2.1).
#pragma once

#include <array>
#include <optional>
#include <span>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/geometry/distance.h"
#include "mrh/geometry/polyhedron.h"

namespace mrh::geometry {

/// A ∩ B as a closed triangle surface wound counter-clockwise seen from outside (world, m).
struct IntersectionVolume {
  /// Unit contact normal, B → A: the penalty force on A points along +n. It is the normalised
  /// Σ S_B − Σ S_A of the triangles' area vectors that lie on B's surface (inside A) and on A's
  /// surface (inside B); the witness direction of the signed distance when that sum vanishes.
  Vec3 n_W = Vec3::UnitZ();
  /// Reference point c: the mean of the vertices (inside the intersection).
  Vec3 c_W = Vec3::Zero();
  std::vector<Vec3> vertices_W;
  std::vector<std::array<int, 3>> triangles;
  double volume = 0.0;  ///< m³ (divergence theorem over the triangles)
  /// Area of the intersection projected on the plane through c normal to n (m²): half the
  /// projected areas of all triangles, since a closed surface covers its shadow twice.
  double projected_area = 0.0;
};

/// The intersection polyhedron of A (bounded) at X_WA and B (bounded or a plane) at X_WB, from
/// their signed distance `d` (A first): vertices by qhull_r halfspace intersection (the
/// Muller–Preparata dual transform, as the geometric IR's contact region), surface by their
/// convex hull. nullopt when they penetrate by less than `touching_tolerance` (m), when the
/// intersection has no volume or when qhull fails. Not RT-safe (allocates).
std::optional<IntersectionVolume> IntersectConvex(const ConvexPolyhedron& a, const Pose& X_WA,
                                                  const ConvexPolyhedron& b, const Pose& X_WB,
                                                  const DistanceResult& d,
                                                  double touching_tolerance = 1e-9);

/// Which triangles a pressure integral runs over.
enum class PressureSurface {
  kClosed,  ///< every triangle: the spring term, Σ = V n for the pressure δ (B2's volume law)
  kUpper,   ///< only the triangles facing +n (B's surface inside A): a pressure field once
};

/// ∫ pressure over the surface as B2 (Hasegawa & Sato 2004) integrates it, with `pressure[k]`
/// the pressure at
/// vertex k (any unit u: u·m² for the force, u·m³ for the moment): vertices p_k relative to c,
/// projected p'_k = p_k − (p_k·n) n, S = (p'_1 − p'_0) × (p'_2 − p'_0); force Σ (Σ_k pressure_k /
/// 6) S, moment about c Σ (Σ_ab w_ab pressure_b p'_a) × S, w_ab = 1/12 (a = b), 1/24 otherwise.
/// For pressure δ_k = (p_k − c)·n over kClosed the force is V n (V: volume).
/// @pre pressure.size() == v.vertices_W.size(). Not RT-safe.
Wrench IntegratePressure(const IntersectionVolume& v, std::span<const double> pressure,
                         PressureSurface surface);

}  // namespace mrh::geometry
