// SPDX-License-Identifier: Apache-2.0
// The contact local model of local-dynamics: semi-implicit Euler + projected
// Gauss–Seidel on the island's contact rows, at the haptic rate.
#include "mrh/render/local_contact_solver.h"

#include <algorithm>
#include <cmath>

#include "mrh/render/local_body.h"

namespace mrh::render {
namespace {

bool Finite(const Vec3& v) {
  return v.allFinite();
}

// Two unit tangents completing the unit normal n to a right-handed frame.
void Tangents(const Vec3& n, Vec3* t1, Vec3* t2) {
  const Vec3 axis = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  *t1 = n.cross(axis).normalized();
  *t2 = n.cross(*t1);
}

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

// (l1, l2) scaled onto the disc |(l1, l2)| <= limit (the elliptic cone).
void ProjectOnDisc(double limit, double* l1, double* l2) {
  // Impulses are far from overflow: the plain root (glibc's hypot costs 6 % of a 1000-contact
  // tick).
  const double mag2 = *l1 * *l1 + *l2 * *l2;
  if (mag2 <= limit * limit) return;
  const double s = mag2 > 0.0 ? limit / std::sqrt(mag2) : 0.0;
  *l1 *= s;
  *l2 *= s;
}

// The friction impulse of an elliptic (disc) cone: the minimiser of ½ xᵀ M x − bᵀ x over the
// disc |x| <= limit, M = [m11 m12; m12 m22] symmetric positive definite (the contact's 2×2
// tangential block of A + R), det = m11 m22 − m12² (constant over a tick's sweeps, so computed
// once per tick). Outside the disc the solution is x = (M + ν I)⁻¹ b with ν > 0 and
// |x| = limit, ν found by Newton's method on |x(ν)|² − limit², which is convex and decreasing
// in ν, so the iterates approach the root from below without overshooting. This is the friction
// the maximum-dissipation principle gives: opposite the sliding velocity in M's metric.
// Projecting the unconstrained x radially instead (the Euclidean metric) would turn the friction
// of a corner whose tangents differ in effective mass away from the slip.
void SolveDisc(double m11, double m12, double m22, double det, double b1, double b2, double limit,
               double* x1, double* x2) {
  if (!(limit > 0.0)) {
    *x1 = 0.0;
    *x2 = 0.0;
    return;
  }
  if (!(det > 0.0)) {  // degenerate block: each tangent on its own
    *x1 = m11 > 0.0 ? b1 / m11 : 0.0;
    *x2 = m22 > 0.0 ? b2 / m22 : 0.0;
    ProjectOnDisc(limit, x1, x2);
    return;
  }
  // y = (M + ν I)⁻¹ r
  const auto apply_inverse = [&](double nu, double r1, double r2, double* y1, double* y2) {
    const double a = m11 + nu, c = m22 + nu;
    const double det_nu = a * c - m12 * m12;
    *y1 = (c * r1 - m12 * r2) / det_nu;
    *y2 = (a * r2 - m12 * r1) / det_nu;
  };
  // x = M⁻¹ b: apply_inverse at ν = 0 with the tick's det (m11, m22 >= +0, so m + 0 is m).
  *x1 = (m22 * b1 - m12 * b2) / det;
  *x2 = (m11 * b2 - m12 * b1) / det;
  const double limit2 = limit * limit;
  if (*x1 * *x1 + *x2 * *x2 <= limit2) return;
  double nu = 0.0;
  for (int it = 0; it < 30; ++it) {
    const double f = *x1 * *x1 + *x2 * *x2 - limit2;
    if (f <= 1e-12 * limit2) break;
    double z1, z2;  // d|x|²/dν = −2 xᵀ (M + ν I)⁻¹ x
    apply_inverse(nu, *x1, *x2, &z1, &z2);
    const double slope = -2.0 * (*x1 * z1 + *x2 * z2);
    if (!(slope < 0.0)) break;
    nu -= f / slope;
    apply_inverse(nu, b1, b2, x1, x2);
  }
  ProjectOnDisc(limit, x1, x2);  // rounding
}

// The relative velocity change (m/s) an impulse change dl (N·s) makes on a row of inverse
// effective mass 1 / inv_w.
double VelocityChange(double dl, double inv_w) {
  return inv_w > 0.0 ? std::abs(dl) / inv_w : 0.0;
}

// The point a row is matched on across periods: the contact point on A, or for a round A the
// core point (the contact point on a rolling body moves over its surface from period to period).
Vec3 WarmKey(const ir::LocalContactRow& c) {
  return c.r_A > 0.0 || c.e_A.x() > 0.0 ? c.s_A : c.p_A;
}

Mat3 InverseOrZero(const Mat3& I) {
  const double det = I.determinant();
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return Mat3::Zero();
  return I.inverse();
}

}  // namespace

// The model's bodies into scratch_, each from its local state when it keeps one (see Adopt;
// none with keep_local_state false).
void LocalContactSolver::AdoptBodies(const ir::LocalContactModel& model, std::size_t n,
                                     bool keep_local_state) noexcept {
  for (std::size_t i = 0; i < n; ++i) {
    const ir::LocalIslandBody& e = model.bodies[i];
    Body& b = scratch_[i];
    b = Body{};
    b.body = e.body;
    b.motion = e.motion;
    b.p_BCm = e.p_BCm;
    b.inv_mass = e.mass > 0.0 ? 1.0 / e.mass : 0.0;
    b.I_B = e.inertia_B;
    b.I_B_inv = InverseOrZero(e.inertia_B);
    b.p = e.X_WB * e.p_BCm;
    b.q = e.X_WB.q.normalized();
    b.v = e.V_WCm.v;
    b.w = e.V_WCm.w;
    for (std::size_t o = 0; keep_local_state && o < count_; ++o) {
      if (bodies_[o].body != e.body || (e.reset && !bodies_[o].pushed)) continue;
      b.p = bodies_[o].p;
      b.q = bodies_[o].q;
      b.v = bodies_[o].v;
      b.w = bodies_[o].w;
      break;
    }
  }
}

void LocalContactSolver::Adopt(const ir::LocalContactModel& model) noexcept {
  AdoptModel(model, true);
}

void LocalContactSolver::Restart(const ir::LocalContactModel& model) noexcept {
  AdoptModel(model, false);
}

void LocalContactSolver::AdoptModel(const ir::LocalContactModel& model,
                                    bool keep_local_state) noexcept {
  SaveWarmStart();
  const std::size_t n = std::min(model.bodies.size(), bodies_.size());
  AdoptBodies(model, n, keep_local_state);
  for (std::size_t i = 0; i < n; ++i) bodies_[i] = scratch_[i];
  count_ = n;
  rows_count_ = 0;
  for (const ir::LocalContactRow& c : model.contacts) {
    if (rows_count_ == rows_.size()) break;
    if (c.a < 0 || static_cast<std::size_t>(c.a) >= n || c.b >= static_cast<int>(n)) continue;
    Row& r = rows_[rows_count_];
    r = Row{};
    r.c = c;
    WarmStart(r, rows_count_++);
  }
  HoldRestingPenetration();
  gravity_ = model.gravity;
  active_ = 0;
}

void LocalContactSolver::SaveWarmStart() noexcept {
  warm_count_ = rows_count_;
  for (std::size_t k = 0; k < rows_count_; ++k) {
    const Row& r = rows_[k];
    warm_[k].a_body = bodies_[static_cast<std::size_t>(r.c.a)].body;
    warm_[k].b_body = r.c.b >= 0 ? bodies_[static_cast<std::size_t>(r.c.b)].body : -1;
    warm_[k].p_A = WarmKey(r.c);
    warm_[k].lambda = r.lambda;
  }
}

// Warm start across periods: the same contact (same bodies, point on A within kMatch) of the
// previous period, looked for near the same row index (the engine emits contacts in a stable
// order), keeps its impulses; the first ticks of a period then need as few sweeps as the others.
void LocalContactSolver::WarmStart(Row& r, std::size_t k) const noexcept {
  constexpr double kMatch = 2e-3;     // m
  constexpr std::size_t kWindow = 8;  // rows either side
  const int a_body = bodies_[static_cast<std::size_t>(r.c.a)].body;
  const int b_body = r.c.b >= 0 ? bodies_[static_cast<std::size_t>(r.c.b)].body : -1;
  const std::size_t lo = k > kWindow ? k - kWindow : 0;
  const std::size_t hi = std::min(warm_count_, k + kWindow + 1);
  for (std::size_t o = lo; o < hi; ++o) {
    const WarmRow& w = warm_[o];
    if (w.a_body != a_body || w.b_body != b_body || (w.p_A - WarmKey(r.c)).norm() > kMatch) {
      continue;
    }
    r.lambda = w.lambda;
    return;
  }
}

// MuJoCo's soft contact rests at a penetration (the load over its contact stiffness) and the
// global step puts it back every period, so pushing it out lifts every pushed body each period
// and the global step drops it again. A body pair's contacts (consecutive rows: the engine
// emits them per geom pair) therefore hold the shallowest penetration among them: a body at
// MuJoCo's rest stays put, while a tilt of the soft contact (deeper rows) is still removed, so a
// pushed box stays level.
void LocalContactSolver::HoldRestingPenetration() noexcept {
  std::size_t first = 0;
  while (first < rows_count_) {
    std::size_t end = first + 1;
    double shallowest = rows_[first].c.dist0;
    while (end < rows_count_ && rows_[end].c.a == rows_[first].c.a &&
           rows_[end].c.b == rows_[first].c.b) {
      shallowest = std::max(shallowest, rows_[end].c.dist0);
      ++end;
    }
    const double hold = settings_.soft_contacts ? 0.0 : std::max(0.0, -shallowest);
    for (std::size_t k = first; k < end; ++k) rows_[k].hold = hold;
    first = end;
  }
}

int LocalContactSolver::FindMotion(int motion) const noexcept {
  for (std::size_t i = 0; i < count_; ++i) {
    if (bodies_[i].motion == motion) return static_cast<int>(i);
  }
  return -1;
}

Pose LocalContactSolver::X_WB(std::size_t i) const noexcept {
  const Body& b = bodies_[i];
  return Pose{b.p - b.q * b.p_BCm, b.q};
}

void LocalContactSolver::AddForce(std::size_t i, const Vec3& f_W, const Vec3& p_W) noexcept {
  Body& b = bodies_[i];
  b.pushed = true;
  b.f += f_W;
  b.tau += (p_W - b.p).cross(f_W);
}

// Free velocities: gravity, the added forces and the gyroscopic term, explicit.
void LocalContactSolver::Integrate(double dt) noexcept {
  for (std::size_t i = 0; i < count_; ++i) {
    Body& b = bodies_[i];
    const Mat3 R = b.q.toRotationMatrix();
    b.I_W_inv = R * b.I_B_inv * R.transpose();
    const Vec3 Iw = R * (b.I_B * (R.transpose() * b.w));
    b.v0 = b.v;
    b.w0 = b.w;
    b.v += dt * (gravity_ + b.inv_mass * b.f);
    b.w += dt * (b.I_W_inv * (b.tau - b.w.cross(Iw)));
  }
}

namespace {

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

// The sweep's two primitives, defined before their callers so that they inline.
inline double LocalContactSolver::RelativeVelocity(const Row& r, int j) const noexcept {
  const auto u = static_cast<std::size_t>(j);
  const Body& A = bodies_[static_cast<std::size_t>(r.c.a)];
  double v = r.d[u].dot(A.v) + r.jA[u].dot(A.w);
  if (r.c.b >= 0) {
    const Body& B = bodies_[static_cast<std::size_t>(r.c.b)];
    v -= r.d[u].dot(B.v) + r.jB[u].dot(B.w);
  }
  return v;
}

inline void LocalContactSolver::ApplyImpulse(Row& r, int j, double dl) noexcept {
  const auto u = static_cast<std::size_t>(j);
  Body& A = bodies_[static_cast<std::size_t>(r.c.a)];
  A.v += (A.inv_mass * dl) * r.d[u];
  A.w += dl * r.mA[u];
  if (r.c.b >= 0) {
    Body& B = bodies_[static_cast<std::size_t>(r.c.b)];
    B.v -= (B.inv_mass * dl) * r.d[u];
    B.w -= dl * r.mB[u];
  }
}

// World frames, lever arms, effective masses and targets of this tick; warm start.
void LocalContactSolver::PrepareRows(double dt) noexcept {
  for (std::size_t k = 0; k < rows_count_; ++k) {
    Row& r = rows_[k];
    const Body& A = bodies_[static_cast<std::size_t>(r.c.a)];
    Vec3 pA = A.p + A.q * (r.c.p_A - A.p_BCm);
    Vec3 pB = r.c.p_B;
    Vec3 n = r.c.n_B;
    Vec3 t = r.c.t_B;
    if (r.c.b >= 0) {
      const Body& B = bodies_[static_cast<std::size_t>(r.c.b)];
      pB = B.p + B.q * (r.c.p_B - B.p_BCm);
      n = B.q * r.c.n_B;
      t = B.q * r.c.t_B;
      if (r.c.r_B > 0.0) {  // B round: its point (and, both round, the normal) follow the cores
        const Vec3 sB = B.p + B.q * (r.c.s_B - B.p_BCm);
        if (r.c.r_A > 0.0) {
          const Vec3 between = A.p + A.q * (r.c.s_A - A.p_BCm) - sB;
          if (between.squaredNorm() > 1e-18) n = between.normalized();
        }
        pB = sB + r.c.r_B * n;
      } else if (r.c.e_B.x() > 0.0) {
        pB = EllipsoidSupport(B.p, B.q, B.p_BCm, r.c.s_B, r.c.q_B, r.c.e_B, n);
      }
      r.rB = pB - B.p;
    }
    const bool round_A = r.c.r_A > 0.0 || r.c.e_A.x() > 0.0;
    if (r.c.r_A > 0.0) pA = A.p + A.q * (r.c.s_A - A.p_BCm) - r.c.r_A * n;  // A's support point
    if (r.c.e_A.x() > 0.0) pA = EllipsoidSupport(A.p, A.q, A.p_BCm, r.c.s_A, r.c.q_A, r.c.e_A, -n);
    r.rA = pA - A.p;
    if (round_A && r.c.b >= 0 && !(r.c.r_B > 0.0 || r.c.e_B.x() > 0.0)) {
      // A round body touches B's face where A's support point meets it, wherever it has rolled
      // or slid along the face since the export: B's lever arm goes there, not to the point
      // fixed on B at the export, or B's torque would not be the moment of the contact force.
      const Body& B = bodies_[static_cast<std::size_t>(r.c.b)];
      r.rB = pA - n.dot(pA - pB) * n - B.p;
    }
    r.d[0] = n;
    FrictionDirections(n, t, r.c.pyramidal, &r.d[1], &r.d[2]);
    for (std::size_t j = 0; j < 3; ++j) {
      r.jA[j] = r.rA.cross(r.d[j]);
      r.mA[j] = A.I_W_inv * r.jA[j];
      double w = A.inv_mass + r.jA[j].dot(r.mA[j]);
      if (r.c.b >= 0) {
        const Body& B = bodies_[static_cast<std::size_t>(r.c.b)];
        r.jB[j] = r.rB.cross(r.d[j]);
        r.mB[j] = B.I_W_inv * r.jB[j];
        w += B.inv_mass + r.jB[j].dot(r.mB[j]);
      }
      r.inv_w[j] = w;  // A_jj for now; SetTargets makes it 1 / (A_jj + R)
    }
    // The tangents are orthogonal, so only the rotations couple them.
    r.a12 = r.jA[1].dot(r.mA[2]) + (r.c.b >= 0 ? r.jB[1].dot(r.mB[2]) : 0.0);
    SetTargets(r, n.dot(pA - pB) + r.hold, dt);
    if (r.lambda[0] > 0.0) {
      for (int j = 0; j < 3; ++j) ApplyImpulse(r, j, r.lambda[static_cast<std::size_t>(j)]);
    }
  }
}

namespace {

// MuJoCo's impedance d(|r|) of solimp (dmin, dmax, width, midpoint, power).
double Impedance(const double* solimp, double depth) {
  const double dmin = solimp[0], dmax = solimp[1], width = solimp[2];
  const double mid = solimp[3], power = solimp[4];
  if (!(width > 0.0) || depth >= width) return std::clamp(dmax, 1e-4, 0.9999);
  const double x = std::max(0.0, depth / width);
  double y = x;
  if (power > 1.0) {
    y = x <= mid ? std::pow(x, power) / std::pow(mid, power - 1.0)
                 : 1.0 - std::pow(1.0 - x, power) / std::pow(1.0 - mid, power - 1.0);
  }
  return std::clamp(dmin + y * (dmax - dmin), 1e-4, 0.9999);
}

}  // namespace

// Targets and effective masses of a row (r.inv_w holds A_jj on entry). An open contact (gap >=
// 0) is hard and speculative: it may close to zero within the tick. A penetrating one is
// MuJoCo's soft constraint (soft_contacts) with the time constant clamped to 2 ticks (MuJoCo's
// refsafe), or hard with a Baumgarte push-out.
void LocalContactSolver::SetTargets(Row& r, double gap, double dt) const noexcept {
  r.R = 0.0;
  r.target = {gap >= 0.0 ? -gap / dt : -settings_.baumgarte * gap / dt, 0.0, 0.0};
  if (settings_.soft_contacts && gap < 0.0) {
    const double dmax = std::clamp(r.c.solimp[1], 1e-4, 0.9999);
    double k = 0.0, b = 0.0;
    if (r.c.solref[0] > 0.0) {
      const double tc = std::max(r.c.solref[0], 2.0 * dt);
      b = 2.0 / (dmax * tc);
      k = 1.0 / (dmax * dmax * tc * tc * r.c.solref[1] * r.c.solref[1]);
    } else {
      k = -r.c.solref[0] / (dmax * dmax);
      b = -r.c.solref[1] / dmax;
    }
    const double imp = Impedance(r.c.solimp, -gap);
    const Body& A = bodies_[static_cast<std::size_t>(r.c.a)];
    const double diag =
        A.inv_mass + (r.c.b >= 0 ? bodies_[static_cast<std::size_t>(r.c.b)].inv_mass : 0.0);
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

// One Gauss–Seidel update of a contact: normal (λ_n >= 0), then the friction of the scene's
// cone (pyramid or disc). Returns the largest change of a relative velocity (m/s).
double LocalContactSolver::SolveRow(Row& r, bool reverse) noexcept {
  const double vn = RelativeVelocity(r, 0);
  const double ln =
      std::max(0.0, r.lambda[0] + (r.target[0] - vn - r.R * r.lambda[0]) * r.inv_w[0]);
  double change = VelocityChange(ln - r.lambda[0], r.inv_w[0]);
  ApplyImpulse(r, 0, ln - r.lambda[0]);
  r.lambda[0] = ln;
  if (r.c.pyramidal) {
    return std::max(change, SolveFrictionBox(r, r.c.mu * ln * std::sqrt(0.5), reverse));
  }
  // The contact's two tangents as one block: M = A_tt + R I, and the unconstrained impulse
  // solves M (l − λ) = target − v − R λ, i.e. M l = b with b = target − v − R λ + M λ.
  const double m11 = r.m11, m22 = r.m22;
  const double g1 = r.target[1] - RelativeVelocity(r, 1) - r.R * r.lambda[1];
  const double g2 = r.target[2] - RelativeVelocity(r, 2) - r.R * r.lambda[2];
  double l1 = 0.0, l2 = 0.0;
  SolveDisc(m11, r.a12, m22, r.det, g1 + m11 * r.lambda[1] + r.a12 * r.lambda[2],
            g2 + r.a12 * r.lambda[1] + m22 * r.lambda[2], r.c.mu * ln, &l1, &l2);
  change = std::max({change, VelocityChange(l1 - r.lambda[1], r.inv_w[1]),
                     VelocityChange(l2 - r.lambda[2], r.inv_w[2])});
  ApplyImpulse(r, 1, l1 - r.lambda[1]);
  ApplyImpulse(r, 2, l2 - r.lambda[2]);
  r.lambda[1] = l1;
  r.lambda[2] = l2;
  return change;
}

// The pyramid's two friction rows one after the other, each clamped to [-limit, limit], in the
// order of the sweep (a fixed order biased a box pushed straight to one side).
double LocalContactSolver::SolveFrictionBox(Row& r, double limit, bool reverse) noexcept {
  double change = 0.0;
  for (int i = 1; i <= 2; ++i) {
    const int j = reverse ? 3 - i : i;
    const double l = std::clamp(
        r.lambda[j] + (r.target[j] - RelativeVelocity(r, j) - r.R * r.lambda[j]) * r.inv_w[j],
        -limit, limit);
    change = std::max(change, VelocityChange(l - r.lambda[j], r.inv_w[j]));
    ApplyImpulse(r, j, l - r.lambda[j]);
    r.lambda[j] = l;
  }
  return change;
}

// Positions from the constrained velocities; non-finite bodies are stopped.
bool LocalContactSolver::Finish(double dt) noexcept {
  bool ok = true;
  active_ = 0;
  for (std::size_t k = 0; k < rows_count_; ++k) active_ += rows_[k].lambda[0] > 0.0 ? 1 : 0;
  for (std::size_t i = 0; i < count_; ++i) {
    Body& b = bodies_[i];
    b.f.setZero();
    b.tau.setZero();
    const Vec3 p = b.p + dt * b.v;
    const Quat q = IntegrateWorldRotation(b.q, b.w, dt);
    if (!Finite(b.v) || !Finite(b.w) || !Finite(p) || !std::isfinite(q.norm())) {
      b.v.setZero();
      b.w.setZero();
      ok = false;
      continue;
    }
    b.p = p;
    b.q = q;
  }
  return ok;
}

bool LocalContactSolver::Step(double dt) noexcept {
  Integrate(dt);
  PrepareRows(dt);
  // Symmetric Gauss–Seidel: the sweep direction alternates, so the order of the rows biases
  // no direction (a box pushed straight stays straight).
  sweeps_ = 0;
  for (int it = 0; it < settings_.iterations; ++it) {
    ++sweeps_;
    double change = 0.0;
    for (std::size_t i = 0; i < rows_count_; ++i) {
      const std::size_t k = (it % 2 == 0) ? i : rows_count_ - 1 - i;
      change = std::max(change, SolveRow(rows_[k], it % 2 != 0));
    }
    if (change <= settings_.tolerance) break;
  }
  return Finish(dt);
}

}  // namespace mrh::render
