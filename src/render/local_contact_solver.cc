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
    b.inv_weight = e.inv_weight > 0.0 ? e.inv_weight : b.inv_mass;
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
  AdoptJoints(model);
  AdoptTrees();
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

// Free velocities: gravity, the added forces and the gyroscopic term, explicit (the bodies of
// joint-space trees: IntegrateTree).
void LocalContactSolver::Integrate(double dt) noexcept {
  for (std::size_t i = 0; i < count_; ++i) {
    Body& b = bodies_[i];
    if (b.tree) continue;  // IntegrateTree; a tree side's rows use M⁻¹, not I_W⁻¹
    const Mat3 R = b.q.toRotationMatrix();
    b.I_W_inv = R * b.I_B_inv * R.transpose();
    const Vec3 Iw = R * (b.I_B * (R.transpose() * b.w));
    b.v0 = b.v;
    b.w0 = b.w;
    b.v += dt * (gravity_ + b.inv_mass * b.f);
    b.w += dt * (b.I_W_inv * (b.tau - b.w.cross(Iw)));
  }
}

// The sweep's two primitives, defined before their callers so that they inline.
inline double LocalContactSolver::RelativeVelocity(const Row& r, int j) const noexcept {
  const auto u = static_cast<std::size_t>(j);
  double v = 0.0;
  if (!r.a_tree) {
    const Body& A = bodies_[static_cast<std::size_t>(r.c.a)];
    v = r.d[u].dot(A.v) + r.jA[u].dot(A.w);
  }
  if (r.c.b >= 0 && !r.b_tree) {
    const Body& B = bodies_[static_cast<std::size_t>(r.c.b)];
    v -= r.d[u].dot(B.v) + r.jB[u].dot(B.w);
  }
  if (r.tree >= 0) v += TreeVelocity(tree_rows_[static_cast<std::size_t>(r.tree)].g[u]);
  return v;
}

inline void LocalContactSolver::ApplyImpulse(Row& r, int j, double dl) noexcept {
  const auto u = static_cast<std::size_t>(j);
  if (!r.a_tree) {
    Body& A = bodies_[static_cast<std::size_t>(r.c.a)];
    A.v += (A.inv_mass * dl) * r.d[u];
    A.w += dl * r.mA[u];
  }
  if (r.c.b >= 0 && !r.b_tree) {
    Body& B = bodies_[static_cast<std::size_t>(r.c.b)];
    B.v -= (B.inv_mass * dl) * r.d[u];
    B.w -= dl * r.mB[u];
  }
  if (r.tree >= 0) ApplyTree(tree_rows_[static_cast<std::size_t>(r.tree)].h[u], dl);
}

// World frames, lever arms, effective masses and targets of this tick; warm start.
void LocalContactSolver::PrepareRows(double dt) noexcept {
  tree_rows_count_ = 0;
  for (std::size_t k = 0; k < rows_count_; ++k) {
    Row& r = rows_[k];
    PrepareRow(r, dt);
    if (r.lambda[0] > 0.0) {
      for (int j = 0; j < 3; ++j) ApplyImpulse(r, j, r.lambda[static_cast<std::size_t>(j)]);
    }
  }
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
    if (b.tree) continue;  // FinishTree
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
  PlaceJoints();  // the trees' axes were placed where their poses last changed (FinishTree)
  AddJointSprings();
  Integrate(dt);
  IntegrateTree(dt);
  PrepareRows(dt);
  PrepareJointRows(dt);
  PrepareDofRows(dt);
  // Symmetric Gauss–Seidel: the sweep direction alternates, so the order of the rows biases
  // no direction (a box pushed straight stays straight). The joints' rows and the trees'
  // coordinate rows come first in a forward sweep and last in a backward one.
  sweeps_ = 0;
  for (int it = 0; it < settings_.iterations; ++it) {
    ++sweeps_;
    const bool forward = it % 2 == 0;
    double change = 0.0;
    for (std::size_t i = 0; forward && i < jrows_count_; ++i) {
      change = std::max(change, SolveJointRow(jrows_[i]));
    }
    if (forward) change = std::max(change, SolveDofRows(true));
    for (std::size_t i = 0; i < rows_count_; ++i) {
      const std::size_t k = forward ? i : rows_count_ - 1 - i;
      change = std::max(change, SolveRow(rows_[k], !forward));
    }
    if (!forward) change = std::max(change, SolveDofRows(false));
    for (std::size_t i = 0; !forward && i < jrows_count_; ++i) {
      change = std::max(change, SolveJointRow(jrows_[jrows_count_ - 1 - i]));
    }
    if (change <= settings_.tolerance) break;
  }
  const bool ok = Finish(dt);
  return FinishTree(dt) && ok;
}

}  // namespace mrh::render
