// SPDX-License-Identifier: Apache-2.0
// A tick's contact rows of the contact local model: world contact points, lever arms, friction
// directions, effective masses and targets (before the Gauss–Seidel sweeps).
#include <algorithm>
#include <cmath>

#include "mrh/render/local_contact_solver.h"
#include "soft_constraint.h"

namespace mrh::render {
namespace {

using internal::Impedance;
using internal::Tangents;

// The friction directions of a row with normal n. Disc: any two tangents. Pyramid: MuJoCo's
// set |f_t1| + |f_t2| <= mu f_n about its contact frame (t1 = the exported tangent t rotated
// like n and made orthogonal to n) is the square |f_e1|, |f_e2| <= mu f_n / sqrt 2 about the
// diagonals e1,2 = (t1 ± t2) / sqrt 2: two independently clamped rows, which Gauss–Seidel solves
// exactly (a Euclidean projection on the pyramid's edges, coupling both, loses a quarter of a
// pushed box's friction and lets it turn away).
void FrictionDirections(const Vec3& n, const Vec3& t, bool pyramidal, Vec3* d1, Vec3* d2) {
  const Vec3 u = t - t.dot(n) * n;
  Vec3 t1, t2;
  if (u.squaredNorm() > 1e-12) {
    t1 = u.normalized();
    t2 = n.cross(t1);
  } else {
    Tangents(n, &t1, &t2);
  }
  if (!pyramidal) {
    *d1 = t1;
    *d2 = t2;
    return;
  }
  *d1 = std::sqrt(0.5) * (t1 + t2);
  *d2 = std::sqrt(0.5) * (t1 - t2);
}

// The point of an ellipsoid (semi-axes e, centre s and orientation q in the body frame of a
// body at position p, orientation q_W, COM offset c) farthest along the world direction u.
Vec3 EllipsoidSupport(const Vec3& p, const Quat& q_W, const Vec3& c, const Vec3& s, const Quat& q,
                      const Vec3& e, const Vec3& u) noexcept {
  const Quat q_WG = q_W * q;
  const Vec3 u_G = q_WG.conjugate() * u;
  const Vec3 eu = e.cwiseProduct(u_G);
  const double norm = eu.norm();
  const Vec3 x_G = norm > 0.0 ? Vec3(e.cwiseProduct(eu) / norm) : Vec3::Zero();
  return p + q_W * (s - c) + q_WG * x_G;
}

}  // namespace

// B's contact point (world), normal and tangent this tick, and B's lever arm: fixed on B, or for
// a round B on its core (both round: the normal joins the cores), or an ellipsoid's support
// point.
void LocalContactSolver::PlaceB(Row& r, Vec3* pB, Vec3* n, Vec3* t) const noexcept {
  const Body& A = bodies_[static_cast<std::size_t>(r.c.a)];
  const Body& B = bodies_[static_cast<std::size_t>(r.c.b)];
  *pB = B.p + B.q * (r.c.p_B - B.p_BCm);
  *n = B.q * r.c.n_B;
  *t = B.q * r.c.t_B;
  if (r.c.r_B > 0.0) {  // B round: its point (and, both round, the normal) follow the cores
    const Vec3 sB = B.p + B.q * (r.c.s_B - B.p_BCm);
    if (r.c.r_A > 0.0) {
      const Vec3 between = A.p + A.q * (r.c.s_A - A.p_BCm) - sB;
      if (between.squaredNorm() > 1e-18) *n = between.normalized();
    }
    *pB = sB + r.c.r_B * *n;
  } else if (r.c.e_B.x() > 0.0) {
    *pB = EllipsoidSupport(B.p, B.q, B.p_BCm, r.c.s_B, r.c.q_B, r.c.e_B, *n);
  }
  r.rB = *pB - B.p;
}

// The row's contact points on A and B (world), normal and tangent this tick; its lever arms.
void LocalContactSolver::PlaceContact(Row& r, Vec3* pA, Vec3* pB, Vec3* n, Vec3* t) const noexcept {
  const Body& A = bodies_[static_cast<std::size_t>(r.c.a)];
  *pA = A.p + A.q * (r.c.p_A - A.p_BCm);
  *pB = r.c.p_B;
  *n = r.c.n_B;
  *t = r.c.t_B;
  if (r.c.b >= 0) PlaceB(r, pB, n, t);
  const bool round_A = r.c.r_A > 0.0 || r.c.e_A.x() > 0.0;
  if (r.c.r_A > 0.0) *pA = A.p + A.q * (r.c.s_A - A.p_BCm) - r.c.r_A * *n;  // A's support point
  if (r.c.e_A.x() > 0.0) {
    *pA = EllipsoidSupport(A.p, A.q, A.p_BCm, r.c.s_A, r.c.q_A, r.c.e_A, -*n);
  }
  r.rA = *pA - A.p;
  if (round_A && r.c.b >= 0 && !(r.c.r_B > 0.0 || r.c.e_B.x() > 0.0)) {
    // A round body touches B's face where A's support point meets it, wherever it has rolled
    // or slid along the face since the export: B's lever arm goes there, not to the point
    // fixed on B at the export, or B's torque would not be the moment of the contact force.
    const Body& B = bodies_[static_cast<std::size_t>(r.c.b)];
    r.rB = *pA - n->dot(*pA - *pB) * *n - B.p;
  }
}

// The row's directions (normal n, friction along t), their angular terms and A_jj in r.inv_w.
// A side in a joint-space tree takes no body terms: SetTreeRow adds its coordinates' share.
void LocalContactSolver::SetDirections(Row& r, const Vec3& n, const Vec3& t) noexcept {
  const Body& A = bodies_[static_cast<std::size_t>(r.c.a)];
  r.a_tree = A.tree;
  r.b_tree = r.c.b >= 0 && bodies_[static_cast<std::size_t>(r.c.b)].tree;
  r.tree = -1;
  r.d[0] = n;
  FrictionDirections(n, t, r.c.pyramidal, &r.d[1], &r.d[2]);
  for (std::size_t j = 0; j < 3; ++j) {
    double w = 0.0;
    if (!r.a_tree) {
      r.jA[j] = r.rA.cross(r.d[j]);
      r.mA[j] = A.I_W_inv * r.jA[j];
      w = A.inv_mass + r.jA[j].dot(r.mA[j]);
    }
    if (r.c.b >= 0 && !r.b_tree) {
      const Body& B = bodies_[static_cast<std::size_t>(r.c.b)];
      r.jB[j] = r.rB.cross(r.d[j]);
      r.mB[j] = B.I_W_inv * r.jB[j];
      w += B.inv_mass + r.jB[j].dot(r.mB[j]);
    }
    r.inv_w[j] = w;  // A_jj for now; SetTargets makes it 1 / (A_jj + R)
  }
  // The tangents are orthogonal, so only the rotations couple them.
  r.a12 = (r.a_tree ? 0.0 : r.jA[1].dot(r.mA[2])) +
          (r.c.b >= 0 && !r.b_tree ? r.jB[1].dot(r.mB[2]) : 0.0);
  if (r.a_tree || r.b_tree) SetTreeRow(r);
}

// World frames, lever arms, effective masses and targets of row r this tick.
void LocalContactSolver::PrepareRow(Row& r, double dt) noexcept {
  Vec3 pA, pB, n, t;
  PlaceContact(r, &pA, &pB, &n, &t);
  SetDirections(r, n, t);
  SetTargets(r, n.dot(pA - pB) + r.hold, dt);
}

// Targets and effective masses of a row (r.inv_w holds A_jj on entry). An open contact (gap >=
// 0) is hard and speculative: it may close to zero within the tick. A penetrating one is
// MuJoCo's soft constraint (soft_contacts) with the time constant clamped to 2 ticks (MuJoCo's
// refsafe), or hard with a Baumgarte push-out.
void LocalContactSolver::SetTargets(Row& r, double gap, double dt) const noexcept {
  r.R = 0.0;
  r.target = {gap >= 0.0 ? -gap / dt : -settings_.baumgarte * gap / dt, 0.0, 0.0};
  if (settings_.soft_contacts && gap < 0.0) {
    double k = 0.0, b = 0.0;
    internal::SpringDamper(r.c.solref, r.c.solimp, dt, &k, &b);
    const double imp = Impedance(r.c.solimp, -gap);
    const Body& A = bodies_[static_cast<std::size_t>(r.c.a)];
    const double diag =
        A.inv_weight + (r.c.b >= 0 ? bodies_[static_cast<std::size_t>(r.c.b)].inv_weight : 0.0);
    r.R = std::max(1e-15, (1.0 - imp) / imp * diag);
    for (int j = 0; j < 3; ++j) {
      const double v0 = RelativeStartVelocity(r, r.d[static_cast<std::size_t>(j)]);
      const double aref = -b * v0 - (j == 0 ? k * imp * gap : 0.0);
      r.target[static_cast<std::size_t>(j)] = v0 + dt * aref;
    }
  }
  for (double& w : r.inv_w) w = w + r.R > 0.0 ? 1.0 / (w + r.R) : 0.0;
  r.m11 = r.inv_w[1] > 0.0 ? 1.0 / r.inv_w[1] : 0.0;
  r.m22 = r.inv_w[2] > 0.0 ? 1.0 / r.inv_w[2] : 0.0;
  r.det = r.m11 * r.m22 - r.a12 * r.a12;
}

double LocalContactSolver::RelativeStartVelocity(const Row& r, const Vec3& dir) const noexcept {
  const Body& A = bodies_[static_cast<std::size_t>(r.c.a)];
  Vec3 v = A.v0 + A.w0.cross(r.rA);
  if (r.c.b >= 0) {
    const Body& B = bodies_[static_cast<std::size_t>(r.c.b)];
    v -= B.v0 + B.w0.cross(r.rB);
  }
  return dir.dot(v);
}

}  // namespace mrh::render
