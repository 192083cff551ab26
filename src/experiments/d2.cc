// SPDX-License-Identifier: Apache-2.0
// Demo D2, articulated mechanisms: the cases, one run of a case and its metrics.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <vector>

#include "d2_impl.h"
#include "experiment_table.h"
#include "experiment_util.h"
#include "mrh/core/error.h"
#include "mrh/engine/engine.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::experiments::internal {
namespace {

constexpr double kPointerRadius = 0.015;  // m, the scenes' pointer sphere
// The bars: mean |f| within 5 %, sd at most 2x, joints within 2 deg or 5 mm RMS.
constexpr double kMeanTolerance = 0.05;
constexpr double kSdRatio = 2.0;
constexpr double kHingeTolerance = 2.0;  // deg
constexpr double kSlideTolerance = 5.0;  // mm

struct Tap final : physics::Recorder {
  void OnTick(const ir::TickRecord& tick) override {
    trace.tick_t.push_back(tick.t);
    trace.force.push_back(tick.rendered_W.f.norm());
  }

  explicit Tap(const std::vector<D2Joint>& joints) : joints_(joints) {}

  // The case's joints by name (ids found at the first step; a name the scene lacks is missing).
  void OnStep(const physics::StepRecord& step, const world::World& world) override {
    if (ids_.empty()) {
      for (const D2Joint& j : joints_) {
        ids_.push_back(world.FindJoint(j.name));
        if (ids_.back() < 0 && missing.empty()) missing = j.name;
      }
    }
    if (!missing.empty()) return;
    trace.step_t.push_back(step.t);
    std::vector<double> q;
    for (const int id : ids_) q.push_back(world.joint_position(id));
    trace.q.push_back(std::move(q));
  }

  std::string missing;  ///< a joint of the case the scene does not have
  D2Trace trace;

 private:
  const std::vector<D2Joint>& joints_;
  std::vector<int> ids_;
};

session::Session MakeSession(const D2Options& o, const D2Case& c, const D2Method& m) {
  const Vec3 d = c.direction.normalized();
  const Vec3 start = c.contact - o.speed * o.touch_time * d;
  const double t_end = o.touch_time + c.push_time;
  const Vec3 end = c.contact + o.speed * c.push_time * d;
  const double duration = t_end + o.after;
  nlohmann::json j;
  j["scene"] = "d2_" + c.name + ".xml";
  j["method"] = m.method;
  j["physics_dt"] = m.physics_dt;
  j["haptic_dt"] = 0.001;
  j["duration"] = duration;
  j["pointer"] = {{"body", "pointer"}, {"radius", kPointerRadius}};
  j["rendering"] = {{"stiffness", o.stiffness}, {"damping", o.rendering_damping}};
  nlohmann::json frames = {{0.0, start.x(), start.y(), start.z(), 1, 0, 0, 0},
                           {t_end, end.x(), end.y(), end.z(), 1, 0, 0, 0},
                           {duration, end.x(), end.y(), end.z(), 1, 0, 0, 0}};
  j["device"] = {{"type", "scripted"}, {"keyframes", frames}};
  return session::ParseSession(j.dump(), ScenesDir(), {},
                               fmt::format("d2 {} ({})", c.name, m.Label()));
}

void WriteTrace(const std::filesystem::path& dir, const std::string& slug, const D2Case& c,
                const D2Trace& tr) {
  Table f({"t", "force_N", "contact"});
  for (std::size_t i = 0; i < tr.tick_t.size(); ++i)
    f.AddFormatted("{:.3f},{:.5f},{}", tr.tick_t[i], tr.force[i], tr.force[i] > 0.0 ? 1 : 0);
  WriteText(dir / (slug + "_force.csv"), f.Csv());
  std::vector<std::string> columns{"t"};
  for (const D2Joint& jt : c.joints) columns.push_back(jt.name + (jt.slide ? "_mm" : "_deg"));
  Table q(columns);
  for (std::size_t s = 0; s < tr.step_t.size(); ++s) {
    std::vector<std::string> cells{fmt::format("{:.3f}", tr.step_t[s])};
    for (std::size_t k = 0; k < c.joints.size(); ++k) {
      const double scale = c.joints[k].slide ? 1e3 : 180.0 / std::numbers::pi;
      cells.push_back(fmt::format("{:.4f}", scale * tr.q[s][k]));
    }
    q.Add(std::move(cells));
  }
  WriteText(dir / (slug + "_joints.csv"), q.Csv());
}

// Joint k of `ref` at time t, linear between its physics steps (the reference steps every 1 ms,
// the runs it is compared with every 20 or 40 ms).
double Sample(const D2Trace& ref, std::size_t k, double t) {
  const auto it = std::lower_bound(ref.step_t.begin(), ref.step_t.end(), t);
  if (it == ref.step_t.begin()) return ref.q.front()[k];
  if (it == ref.step_t.end()) return ref.q.back()[k];
  const std::size_t i = static_cast<std::size_t>(it - ref.step_t.begin());
  const double t0 = ref.step_t[i - 1], t1 = ref.step_t[i];
  const double a = t1 > t0 ? (t - t0) / (t1 - t0) : 1.0;
  return ref.q[i - 1][k] + a * (ref.q[i][k] - ref.q[i - 1][k]);
}

// RMS over the window's physics steps of joint k's difference from the reference.
double JointRms(const D2Trace& tr, const D2Trace& ref, std::size_t k, double from, double to) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t s = 0; s < tr.step_t.size(); ++s) {
    if (tr.step_t[s] < from || tr.step_t[s] > to) continue;
    const double e = tr.q[s][k] - Sample(ref, k, tr.step_t[s]);
    sum += e * e;
    ++n;
  }
  return n > 0 ? std::sqrt(sum / n) : 0.0;
}

}  // namespace

std::string D2Method::Label() const {
  if (method == "single-rate" || std::abs(physics_dt - 0.02) < 1e-12) return method;
  return fmt::format("{}@{:g}ms", method, physics_dt * 1e3);
}

D2Options DefaultD2Options() {
  D2Options o;
  const double lamp_top = 0.32377 + 0.012 + kPointerRadius;  // upper arm's top at x = 0.3 m
  o.cases = {
      {"lamp",
       Vec3(0.30, 0.0, lamp_top),
       -Vec3::UnitZ(),
       2.0,
       {{"shoulder", false}, {"elbow", false}, {"neck", false}}},
      {"door", Vec3(0.30, -0.01 - kPointerRadius, 0.3), Vec3::UnitY(), 2.5, {{"hinge", false}}},
      {"drawer",
       Vec3(-0.02 - kPointerRadius, 0.0, 0.3),
       Vec3::UnitX(),
       3.0,
       {{"slide", true}},
       2.0,
       0.5},
      {"lever", Vec3(-0.015 - kPointerRadius, 0.0, 0.3), Vec3::UnitX(), 2.5, {{"pivot", false}}},
  };
  o.runs = {{"single-rate", 0.001, false},
            {"local-dynamics", 0.02, true},
            {"local-dynamics-6dof", 0.02, true}};
  return o;
}

D2Options FullD2Options() {
  D2Options o = DefaultD2Options();
  o.runs.push_back({"local-dynamics", 0.04, false});
  o.runs.push_back({"local-dynamics-6dof", 0.04, false});
  return o;
}

D2Trace RunD2Case(const std::filesystem::path& out, const D2Options& o, const D2Case& c,
                  const D2Method& m) {
  auto engine = session::MakeEngine(MakeSession(o, c, m));
  Tap tap(c.joints);
  engine->Run(&tap);
  if (!tap.missing.empty()) {
    throw RuntimeError(fmt::format("d2: scenes/d2_{}.xml has no joint '{}', which the driver reads",
                                   c.name, tap.missing));
  }
  if (!out.empty()) {
    std::filesystem::create_directories(out / "runs");
    WriteTrace(out / "runs", c.name + "_" + Slug(m.Label(), '_'), c, tap.trace);
  }
  return std::move(tap.trace);
}

D2Metrics AnalyzeD2(const D2Options& o, const D2Case& c, const D2Trace& tr, const D2Trace& ref) {
  const double from = o.touch_time + o.settle, to = o.touch_time + c.push_time;
  const double steady = o.touch_time + o.steady_from;
  D2Metrics r;
  double sum = 0.0, sum2 = 0.0, steady_sum = 0.0;
  int n = 0, lost = 0, steady_n = 0;
  for (std::size_t i = 0; i < tr.tick_t.size(); ++i) {
    const double t = tr.tick_t[i], f = tr.force[i];
    if (t < from || t > to) continue;
    sum += f;
    sum2 += f * f;
    lost += f > 0.0 ? 0 : 1;
    ++n;
    if (t >= steady) steady_sum += f, ++steady_n;
  }
  r.mean_force = n > 0 ? sum / n : 0.0;
  r.sd_force = n > 1 ? std::sqrt(std::max(0.0, sum2 / n - r.mean_force * r.mean_force)) : 0.0;
  r.contact_lost = n > 0 ? static_cast<double>(lost) / n : 1.0;
  r.steady_force = steady_n > 0 ? steady_sum / steady_n : 0.0;
  if (&tr == &ref) return r;
  for (std::size_t k = 0; k < c.joints.size(); ++k) {
    const double e = JointRms(tr, ref, k, from, to);
    double& worst = c.joints[k].slide ? r.slide_rms_mm : r.hinge_rms_deg;
    worst = std::max(worst, e * (c.joints[k].slide ? 1e3 : 180.0 / std::numbers::pi));
  }
  return r;
}

D2Bars D2Check(const D2Metrics& r, const D2Metrics& ref) {
  D2Bars b;
  b.mean = std::abs(r.mean_force - ref.mean_force) <= kMeanTolerance * ref.mean_force;
  b.sd = r.sd_force <= kSdRatio * ref.sd_force;
  b.lost = r.contact_lost <= ref.contact_lost;
  b.joints = r.hinge_rms_deg <= kHingeTolerance && r.slide_rms_mm <= kSlideTolerance;
  return b;
}

}  // namespace mrh::experiments::internal
