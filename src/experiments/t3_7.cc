// SPDX-License-Identifier: Apache-2.0
// Experiment t3.7: the 6-DOF methods on ordinary objects (scenes/t3_7_*.xml: sphere, lying
// capsule, upright cylinder, ellipsoid, convex mesh, compound body), pushed centred and off
// centre at 0.1 m/s by a frictionless box or sphere pointer, against a consistent reference — the
// tool as a rigid MuJoCo body at 1 ms (virtual coupling with the rendering's gains) — and against
// what mechanics predicts: a steady slide costs Coulomb's μ m g, a round body rolls at v / r and is
// never thrown faster than a few times the pointer's speed.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <vector>

#include "experiment_table.h"
#include "experiment_util.h"
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"
#include "t3_7_impl.h"

namespace mrh::experiments::internal {
namespace {

session::Session MakeSession(const Case& c, const Variant& v) {
  nlohmann::json j;
  j["scene"] = fmt::format("t3_7_{}.xml", c.shape->name);
  j["method"] = v.method;
  j["physics_dt"] = v.physics_dt;
  j["haptic_dt"] = 0.001;
  j["duration"] = kDuration;
  j["pointer"] = {{"body", c.pointer->body}};
  j["rendering"] = {{"stiffness", kStiffness},
                    {"damping", kDamping},
                    {"rot_stiffness", kRotStiffness},
                    {"friction", 0.0},
                    {"torque_model", "contact"},
                    {"coupling_stiffness", kStiffness},
                    {"coupling_damping", kDamping},
                    {"coupling_rot_stiffness", kRotStiffness},
                    {"tool_mass", kToolMass},
                    {"tool_inertia", {kToolInertia, kToolInertia, kToolInertia}}};
  j["safety"] = {{"ramp", false}};
  const double x0 = -c.shape->reach - c.pointer->reach - kSpeed * kTouch;
  const double x1 = x0 + kSpeed * kDuration;
  j["device"] = {{"type", "scripted"},
                 {"keyframes",
                  {{0.0, x0, c.y, c.shape->push_z, 1, 0, 0, 0},
                   {kDuration, x1, c.y, c.shape->push_z, 1, 0, 0, 0}}}};
  return session::ParseSession(j.dump(), ScenesDir(), {},
                               fmt::format("t3.7 {} ({})", c.Name(), v.label));
}

// Rendered |f| per tick; the object's state per step.
struct Tap final : physics::Recorder {
  void OnTick(const ir::TickRecord& tick) override {
    t.push_back(tick.t);
    f.push_back(tick.rendered_W.f.norm());
    f_W.push_back(tick.rendered_W.f);
  }

  void OnStep(const physics::StepRecord& step, const world::World& world) override {
    if (object < 0) {
      object = world.FindBody("object");
      mass = world.body(object).mass;
      g = world.gravity().norm();
    }
    steps.push_back({step.t, world.body_state(object)});
  }

  struct Step {
    double t;
    world::BodyState state;
  };

  int object = -1;
  double mass = 0.0, g = 0.0;  // kg, m/s²
  std::vector<double> t, f;
  std::vector<Vec3> f_W;
  std::vector<Step> steps;
};

// Heading of the body's x axis about +z (rad): the turn of a body that does not roll.
double Yaw(const Quat& q) {
  const Mat3 R = q.toRotationMatrix();
  return std::atan2(R(1, 0), R(0, 0));
}

T37Result Analyze(const Case& c, const Variant& v, const Tap& tap) {
  T37Result r;
  r.shape = c.shape->name;
  r.pointer = c.pointer->name;
  r.offcentre = c.y != 0.0;
  r.method = v.label;
  // A steady slide, the push Coulomb's μ m g: a centred push that holds the object straight.
  const bool steady = c.y == 0.0 && (c.pointer->face || c.shape->round_side);
  r.coulomb_f = c.shape->motion == Motion::kSlides && steady ? kFriction * tap.mass * tap.g : 0.0;
  r.rolling_radius = c.shape->radius;
  double s = 0.0, ss = 0.0, n = 0.0;
  for (std::size_t i = 0; i < tap.t.size(); ++i) {
    if (tap.t[i] >= kTouch - 0.1 && i > 0) r.impulse += tap.f_W[i] * (tap.t[i] - tap.t[i - 1]);
    if (tap.t[i] < kFrom) continue;
    s += tap.f[i];
    ss += tap.f[i] * tap.f[i];
    n += 1.0;
  }
  r.mean_f = n > 0.0 ? s / n : 0.0;
  r.sd_f = n > 0.0 ? std::sqrt(std::max(0.0, ss / n - r.mean_f * r.mean_f)) : 0.0;
  for (const Tap::Step& step : tap.steps) {
    if (step.t < kTouch - 0.1) continue;  // a 20 ms step first drops a resting body (g Δt)
    r.peak_speed = std::max(r.peak_speed, step.state.V_WCm.v.norm());
    r.peak_spin = std::max(r.peak_spin, step.state.V_WCm.w.norm());
  }
  if (!tap.steps.empty()) {
    const world::BodyState& end = tap.steps.back().state;
    r.end = end.p_WCm;
    r.yaw = Yaw(end.X_WB.q);
  }
  return r;
}

void WriteRun(const std::filesystem::path& dir, const std::string& slug, const Tap& tap) {
  Table f({"t", "force_N"});
  for (std::size_t i = 0; i < tap.t.size(); ++i)
    f.AddFormatted("{:.3f},{:.5f}", tap.t[i], tap.f[i]);
  WriteText(dir / (slug + "_force.csv"), f.Csv());
  Table b({"t", "x", "y", "z", "yaw_rad", "speed_mps", "spin_radps"});
  for (const Tap::Step& s : tap.steps) {
    const world::BodyState& st = s.state;
    b.AddFormatted("{:.3f},{:.6f},{:.6f},{:.6f},{:.5f},{:.5f},{:.5f}", s.t, st.p_WCm.x(),
                   st.p_WCm.y(), st.p_WCm.z(), Yaw(st.X_WB.q), st.V_WCm.v.norm(),
                   st.V_WCm.w.norm());
  }
  WriteText(dir / (slug + "_object.csv"), b.Csv());
}

}  // namespace

std::vector<Case> Cases(const T37Options& options) {
  std::vector<Case> cases;
  for (const PointerKind& p : kPointers) {
    if (std::find(options.pointers.begin(), options.pointers.end(), p.name) ==
        options.pointers.end()) {
      continue;
    }
    for (const Shape& s : kShapes) {
      if (!options.shapes.empty() &&
          std::find(options.shapes.begin(), options.shapes.end(), s.name) == options.shapes.end()) {
        continue;
      }
      cases.push_back({&s, &p, 0.0});
      if (options.offcentre) cases.push_back({&s, &p, p.offset});
    }
  }
  return cases;
}

T37Verdict Judge(const T37Result& r, const T37Result& ref) {
  T37Verdict v;
  // What the push allows, or where gravity adds speed (the ellipsoid), what the reference shows.
  v.speed_bound = kThrowBar * std::max(kSpeed, ref.peak_speed);
  v.thrown = r.peak_speed > v.speed_bound;
  if (r.rolling_radius > 0.0) {
    v.spin_bound = kThrowBar * std::max(kSpeed / r.rolling_radius, ref.peak_spin);
    v.spun = r.peak_spin > v.spin_bound;
  }
  if (r.coulomb_f > 0.0) {
    v.slide_error = r.mean_f / r.coulomb_f - 1.0;
    v.slide_ok = std::abs(*v.slide_error) <= kSlideBar;
  }
  // Off centre, a body that slides follows the reference: the push it took (the impulse ∫f dt
  // from the touch on, a vector: a push that turns the body off the pointer face ends early and
  // deflects it; the coupled tool's ringing averages out of it, not out of |f|), where it
  // went and which way it turned. A rolling body is kicked and rolls away freely: where it
  // stops is the kick's, not the push's, so it has only the speed and spin bars.
  if (r.offcentre && r.rolling_radius == 0.0) {
    const double ref_j = ref.impulse.norm();
    v.force_vs_ref = ref_j > 0.0 ? (r.impulse - ref.impulse).norm() / ref_j : 0.0;
    v.pose_error = (r.end.head<2>() - ref.end.head<2>()).norm();
    v.follows_ref = std::abs(*v.force_vs_ref) <= kForceBar && *v.pose_error <= kPoseBar;
    if (std::abs(ref.yaw) >= kTurnFloor) {
      v.same_turn = std::abs(r.yaw) >= kTurnFloor && (r.yaw > 0.0) == (ref.yaw > 0.0);
    }
  }
  return v;
}

std::vector<T37Result> RunT37Cases(const std::filesystem::path& out, bool quiet,
                                   const T37Options& options) {
  std::filesystem::create_directories(out / "runs");
  std::vector<T37Result> results;
  for (const Case& c : Cases(options)) {
    for (const Variant& v : kVariants) {
      if (!quiet) std::cout << "t3.7: " << c.Name() << " / " << v.label << "...\n";
      auto engine = session::MakeEngine(MakeSession(c, v));
      Tap tap;
      engine->Run(&tap);
      WriteRun(out / "runs", RunSlug(c, v), tap);
      results.push_back(Analyze(c, v, tap));
    }
  }
  return results;
}

}  // namespace mrh::experiments::internal
