// SPDX-License-Identifier: Apache-2.0
// Experiment t3.6: a box pointer pushes, turns, tips and presses boxes on a floor (and, reported
// as open, pushes a box with its inner edge on the box's centre line and at its side edge);
// proxy-6dof at 1 and 20 ms and local-dynamics-6dof at 20 ms with the contact torque model,
// against a consistent reference — the tool as a rigid MuJoCo body at 1 ms (virtual coupling
// with the rendering's gains and the scene's tool–box friction) — and against mechanics:
// Coulomb's μ Σm g where the boxes slide steadily.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <vector>

#include "experiment_table.h"
#include "experiment_util.h"
#include "experiments_impl.h"
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"
#include "t3_6_impl.h"

namespace mrh::experiments::internal {
namespace t36 {

std::string RunSlug(const Case& c, const Variant& v) {
  return std::string(c.name) + "_" + Slug(v.label, '_');
}

}  // namespace t36

namespace {

using namespace t36;  // NOLINT(google-build-using-namespace): the experiment's own constants

session::Session MakeSession(const Case& c, const Variant& v) {
  nlohmann::json j;
  j["scene"] = c.scene;
  j["method"] = v.method;
  j["physics_dt"] = v.physics_dt;
  j["haptic_dt"] = 0.001;
  j["duration"] = kDuration;
  j["rendering"] = {{"stiffness", kStiffness},
                    {"damping", kDamping},
                    {"rot_stiffness", kRotStiffness},
                    {"friction", c.tool_mu},
                    {"torque_model", "contact"},
                    {"coupling_stiffness", kStiffness},
                    {"coupling_damping", kDamping},
                    {"coupling_rot_stiffness", kRotStiffness},
                    {"tool_mass", kToolMass},
                    {"tool_inertia", {kToolInertia, kToolInertia, kToolInertia}}};
  j["safety"] = {{"ramp", false}};
  const double x_end = kX0 + kSpeed * c.push_until;
  const double y = c.y + v.dy;
  nlohmann::json frames = {{0.0, kX0, y, c.z, 1, 0, 0, 0},
                           {c.push_until, x_end, y, c.z, 1, 0, 0, 0}};
  if (c.push_until < kDuration) frames.push_back({kDuration, x_end, y, c.z, 1, 0, 0, 0});
  j["device"] = {{"type", "scripted"}, {"keyframes", frames}};
  return session::ParseSession(j.dump(), ScenesDir(), {},
                               fmt::format("t3.6 {} ({})", c.name, v.label));
}

// Rendered |f|, |τ| per tick; the first box's x and tilt angle and every box's COM per step.
struct Tap final : physics::Recorder {
  void OnTick(const ir::TickRecord& tick) override {
    t.push_back(tick.t);
    f.push_back(tick.rendered_W.f.norm());
    tau.push_back(tick.rendered_W.tau.norm());
    tau_W.push_back(tick.rendered_W.tau);
  }

  void OnStep(const physics::StepRecord& step, const world::World& world) override {
    if (boxes.empty()) {
      for (const char* name : {"box", "box2"}) {
        const int b = world.FindBody(name);
        if (b >= 0) {
          boxes.push_back(b);
          mass += world.body(b).mass;
        }
      }
      g = world.gravity().norm();
    }
    Step s{step.t, {}, 0.0, 0.0, 0.0, 0.0};
    for (const int b : boxes) {
      const world::BodyState st = world.body_state(b);
      s.p.push_back(st.p_WCm);
      s.spin = std::max(s.spin, st.V_WCm.w.norm());
      s.speed = std::max(s.speed, st.V_WCm.v.norm());
    }
    const Quat q = world.body_state(boxes[0]).X_WB.q;
    s.angle = 2.0 * std::acos(std::min(1.0, std::abs(q.w())));
    const Vec3 x_W = q * Vec3::UnitX();
    s.yaw = std::atan2(x_W.y(), x_W.x());
    steps.push_back(std::move(s));
  }

  struct Step {
    double t;
    std::vector<Vec3> p;
    double spin, angle, speed, yaw;
  };

  std::vector<int> boxes;
  double mass = 0.0, g = 0.0;  // kg, the boxes' total; m/s²
  std::vector<double> t, f, tau;
  std::vector<Vec3> tau_W;
  std::vector<Step> steps;
};

void MeanSd(const std::vector<double>& t, const std::vector<double>& x, double* mean, double* sd) {
  double s = 0.0, s2 = 0.0, n = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < kFrom) continue;
    s += x[i];
    s2 += x[i] * x[i];
    n += 1.0;
  }
  *mean = n > 0 ? s / n : 0.0;
  *sd = n > 0 ? std::sqrt(std::max(0.0, s2 / n - *mean * *mean)) : 0.0;
}

T36Result Analyze(const Case& c, const Tap& tap) {
  T36Result r;
  r.sliding_f = c.slide_mu * tap.mass * tap.g;
  MeanSd(tap.t, tap.f, &r.mean_f, &r.sd_f);
  MeanSd(tap.t, tap.tau, &r.mean_tau, &r.sd_tau);
  double n = 0.0;
  for (std::size_t i = 0; i < tap.t.size(); ++i) {
    if (tap.t[i] < kFrom) continue;
    r.mean_tau_W += tap.tau_W[i];
    n += 1.0;
  }
  if (n > 0.0) r.mean_tau_W /= n;
  for (const Tap::Step& s : tap.steps) {
    r.peak_spin = std::max(r.peak_spin, s.spin);
    if (s.t >= kSpeedFrom) r.peak_speed = std::max(r.peak_speed, s.speed);
    if (s.t <= kPoseAt + 1e-9) {
      r.pose_at = s.p;
      r.yaw_at = s.yaw;
    }
  }
  return r;
}

void WriteRun(const std::filesystem::path& dir, const std::string& slug, const Tap& tap) {
  Table f({"t", "force_N", "torque_Nm"});
  for (std::size_t i = 0; i < tap.t.size(); ++i) {
    f.AddFormatted("{:.3f},{:.5f},{:.5f}", tap.t[i], tap.f[i], tap.tau[i]);
  }
  WriteText(dir / (slug + "_wrench.csv"), f.Csv());
  // The first box's pose, the boxes' peak spin and speed; a second box's (row) position.
  Table b({"t", "x", "y", "z", "tilt_rad", "spin_radps", "speed_mps", "x2", "y2", "z2"});
  for (const Tap::Step& s : tap.steps) {
    const Vec3 p2 = s.p.size() > 1 ? s.p[1] : Vec3::Constant(std::nan(""));
    b.AddFormatted("{:.3f},{:.6f},{:.6f},{:.6f},{:.6f},{:.5f},{:.5f},{:.6f},{:.6f},{:.6f}", s.t,
                   s.p[0].x(), s.p[0].y(), s.p[0].z(), s.angle, s.spin, s.speed, p2.x(), p2.y(),
                   p2.z());
  }
  WriteText(dir / (slug + "_box.csv"), b.Csv());
}

}  // namespace

std::vector<std::vector<T36Result>> RunT36Cases(const std::filesystem::path& out, bool quiet) {
  std::filesystem::create_directories(out / "runs");
  std::vector<std::vector<T36Result>> results;
  for (const Case& c : kCases) {
    results.emplace_back();
    for (const Variant& v : kVariants) {
      if (!quiet) std::cout << "t3.6: " << c.name << " / " << v.label << "...\n";
      auto engine = session::MakeEngine(MakeSession(c, v));
      Tap tap;
      engine->Run(&tap);
      WriteRun(out / "runs", RunSlug(c, v), tap);
      T36Result r = Analyze(c, tap);
      r.case_name = c.name;
      r.method = v.label;
      results.back().push_back(std::move(r));
    }
  }
  return results;
}

}  // namespace mrh::experiments::internal
