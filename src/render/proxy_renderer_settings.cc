// SPDX-License-Identifier: Apache-2.0
// Validation of the 6-DOF proxy's settings and the rotation weight R_w.
#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>

#include "mrh/core/error.h"
#include "mrh/core/validate.h"
#include "mrh/render/proxy_renderer.h"

namespace mrh::render {
namespace {

// R_w counts as symmetric when |R − Rᵀ| is within this fraction of its largest entry.
constexpr double kSymmetryTolerance = 1e-12;

std::string Text(double value) {
  return FormatNumber(value);
}

std::string Text(const Mat3& m) {
  std::string text = "[";
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) text += (c > 0 ? " " : r > 0 ? "; " : "") + Text(m(r, c));
  }
  return text + "]";
}

void RequireNonNegative(double value, const char* field, const char* unit) {
  mrh::RequireNonNegative(value, std::string("ProxyRendererSettings.") + field, unit);
}

bool IsSymmetricPositiveDefinite(const Mat3& m) {
  if (!m.allFinite()) return false;
  const double scale = m.cwiseAbs().maxCoeff();
  if ((m - m.transpose()).cwiseAbs().maxCoeff() > kSymmetryTolerance * scale) return false;
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(m, Eigen::EigenvaluesOnly);
  return eigen.eigenvalues().minCoeff() > 0.0;
}

}  // namespace

void ProxyRendererSettings::Validate() const {
  RequireNonNegative(k_t, "k_t", "N/m");
  RequireNonNegative(d_t, "d_t", "N·s/m");
  RequireNonNegative(k_r, "k_r", "N·m/rad");
  RequireNonNegative(d_r, "d_r", "N·m·s/rad");
  RequireNonNegative(mu, "mu", "(friction coefficient)");
  RequireNonNegative(tolerance, "tolerance", "m");
  if (!IsSymmetricPositiveDefinite(rotation_weight)) {
    throw InvalidArgument("ProxyRendererSettings.rotation_weight = " + Text(rotation_weight) +
                          " m²; expected a finite symmetric positive definite matrix; use "
                          "RotationWeightFromInertia or a positive diagonal");
  }
  if (torque_model == ProxyTorqueModel::kContact && !(k_t > 0.0 && k_r > 0.0 && d_r == 0.0)) {
    throw InvalidArgument("ProxyRendererSettings: k_t = " + Text(k_t) + " N/m, k_r = " + Text(k_r) +
                          " N·m/rad, d_r = " + Text(d_r) +
                          " N·m·s/rad; the contact torque model needs k_t > 0, k_r > 0 (R_w = "
                          "k_r / k_t) and d_r = 0 (it damps through the contacts)");
  }
  if (max_iterations < 1 || max_iterations > kMaxProxyIterations) {
    throw InvalidArgument(
        "ProxyRendererSettings.max_iterations = " + std::to_string(max_iterations) +
        "; expected 1.." + std::to_string(kMaxProxyIterations) + "; set a sweep budget (20–50)");
  }
  if (!(max_pair_force > 0.0)) {  // +inf allowed: unbounded
    throw InvalidArgument("ProxyRendererSettings.max_pair_force = " + Text(max_pair_force) +
                          " N; expected > 0 (infinity: unbounded); give the device's max_force");
  }
  if (max_rows < 1 || max_rows > kMaxProxyRows) {
    throw InvalidArgument("ProxyRendererSettings.max_rows = " + std::to_string(max_rows) +
                          "; expected 1.." + std::to_string(kMaxProxyRows) +
                          "; set it to 2 × the contact points you expect (or leave the default)");
  }
}

Mat3 RotationWeightFromInertia(const Mat3& unit_mass_inertia, double scale) {
  if (!(std::isfinite(scale) && scale > 0.0)) {
    throw InvalidArgument("RotationWeightFromInertia: scale = " + Text(scale) +
                          "; expected finite and > 0; set rotation_weight_scale > 0");
  }
  if (!IsSymmetricPositiveDefinite(unit_mass_inertia)) {
    throw InvalidArgument(
        "RotationWeightFromInertia: unit_mass_inertia = " + Text(unit_mass_inertia) +
        " m²; expected a finite symmetric positive definite tensor; give the "
        "pointer's inertia for mass 1 kg");
  }
  return scale * unit_mass_inertia;
}

}  // namespace mrh::render
