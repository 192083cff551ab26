// SPDX-License-Identifier: Apache-2.0
// The grasp experiment's slide case: two simulated fingertips squeeze a box resting on a floor
// with friction and drag it sideways, only their own friction holding it.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiment_table.h"
#include "experiment_util.h"
#include "experiments_impl.h"
#include "mrh/session/session.h"
#include "pointer_tap.h"

namespace mrh::experiments::internal {
namespace {

constexpr double kFingerRadius = 0.01;  // m, the scene's fingertips
constexpr double kBoxHalfWidth = 0.05;  // m, along y
constexpr double kHeight = 0.03;        // m, the box's mid-height
constexpr double kStiffness = 800.0;    // N/m
constexpr double kDamping = 2.0;        // N·s/m
constexpr double kFriction = 0.8;       // at the fingertips
constexpr double kFloorMu = 0.5;        // the scene's box–floor friction
constexpr double kGravity = 9.81;       // m/s², the scene's
constexpr double kTravel = 0.1;         // m along +x
// The script: open → grip by 0.5 s (the hands aim 18 mm past the faces, about 4 N per finger as
// in the lift case), still until 0.8 s, then along +x at 0.1 m/s until 1.8 s, held until 2.3 s,
// open again by 2.8 s.
constexpr double kGripAt = 0.5, kPushAt = 0.8, kStopAt = 1.8, kHoldUntil = 2.3, kOpenAt = 2.8;
constexpr double kDuration = 3.0;  // s
// Statistics: the steady slide, 0.3 s after the push starts, to its end.
constexpr double kFrom = 1.1, kTo = 1.8;  // s

nlohmann::json Keyframes(int finger) {
  const double side = finger == 0 ? -1.0 : 1.0;
  const double open = side * (kBoxHalfWidth + kFingerRadius + 0.01);
  const double grip = side * (kBoxHalfWidth + kFingerRadius - 0.018);
  const auto at = [](double t, double x, double y) {
    return nlohmann::json{t, x, y, kHeight, 1, 0, 0, 0};
  };
  return {at(0.0, 0.0, open),         at(kGripAt, 0.0, grip),        at(kPushAt, 0.0, grip),
          at(kStopAt, kTravel, grip), at(kHoldUntil, kTravel, grip), at(kOpenAt, kTravel, open)};
}

session::Session MakeSession(const GraspRun& run) {
  nlohmann::json j;
  j["scene"] = "two_finger_slide.xml";
  j["method"] = run.method;
  j["physics_dt"] = run.physics_dt;
  j["haptic_dt"] = 0.001;
  j["duration"] = kDuration;
  j["rendering"] = {{"stiffness", kStiffness}, {"damping", kDamping}, {"friction", kFriction}};
  j["pointers"] = nlohmann::json::array();
  const char* bodies[] = {"thumb", "index"};
  for (int finger = 0; finger < 2; ++finger) {
    j["pointers"].push_back({{"body", bodies[finger]},
                             {"radius", kFingerRadius},
                             {"device", {{"type", "hand"}, {"keyframes", Keyframes(finger)}}}});
  }
  return session::ParseSession(
      j.dump(), ScenesDir(), {},
      fmt::format("grasp slide ({} at {} ms)", run.method, run.physics_dt * 1e3));
}

void WriteRun(const std::filesystem::path& dir, const std::string& slug, const PointerTap& tap) {
  Table f({"t", "thumb_N", "index_N", "push_N"});
  const auto& a = tap.forces(0);
  const auto& b = tap.forces(1);
  for (std::size_t k = 0; k < a.size() && k < b.size(); ++k) {
    f.AddFormatted("{:.3f},{:.5f},{:.5f},{:.5f}", a[k].t, a[k].f.norm(), b[k].f.norm(),
                   -(a[k].f.x() + b[k].f.x()));
  }
  WriteText(dir / (slug + "_force.csv"), f.Csv());
  Table x({"t", "box_x", "box_y", "box_z"});
  for (const PointerTap::Step& s : tap.steps()) {
    x.AddFormatted("{:.3f},{:.6f},{:.6f},{:.6f}", s.t, s.p[0].x(), s.p[0].y(), s.p[0].z());
  }
  WriteText(dir / (slug + "_box.csv"), x.Csv());
}

}  // namespace

SlideResult RunSlideCase(const std::filesystem::path& out, const GraspRun& run) {
  auto engine = session::MakeEngine(MakeSession(run));
  PointerTap tap({"box"});
  engine->Run(&tap);
  const std::string slug = "slide_" + Slug(run.method, '_');
  if (!out.empty()) {
    std::filesystem::create_directories(out / "runs");
    WriteRun(out / "runs", slug, tap);
  }
  SlideResult r;
  r.box_mass = tap.mass(0);
  r.floor_mu = kFloorMu;
  r.fingers_travel = kTravel;
  for (int finger = 0; finger < 2; ++finger) {
    const ForceStats s = WindowForce(tap.forces(finger), kFrom, kTo);
    r.mean_force[finger] = s.mean_norm;
    r.sd_force[finger] = s.sd_norm;
    r.push_force -= s.mean.x();
    r.carried -= s.mean.z();
  }
  r.coulomb = kFloorMu * (r.box_mass * kGravity - r.carried);
  const std::vector<PointerTap::Step>& steps = tap.steps();
  for (const PointerTap::Step& s : steps) {
    if (s.t <= kHoldUntil + 1e-9) r.box_travel = s.p[0].x() - steps.front().p[0].x();
  }
  return r;
}

// The lift case's bars, on the slide: each finger's mean force within 5 % of the reference's and
// its sd at most 2x; the box where the reference left it, within 5 mm.
bool MeetsSlideBars(const SlideResult& r, const SlideResult& ref) {
  return std::abs(r.box_travel - ref.box_travel) <= 0.005 &&
         FingersMeetBars(r.mean_force, r.sd_force, ref.mean_force, ref.sd_force);
}

namespace {

std::string SlideScript(const std::vector<GraspRun>& runs) {
  std::string gp =
      "# grasp, slide: each finger's |f|, their push along x and the box's x per method.\n"
      "# gnuplot grasp_slide.gp\n"
      "set terminal pngcairo size 1200,700 enhanced font ',9'\nset output 'grasp_slide.png'\n"
      "set datafile separator ','\nset grid\nset key top right\nset multiplot layout 2,1\n"
      "set title 'finger force |f| and push -sum f_x (N)'\nset xlabel 't (s)'\nplot ";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string slug = "runs/slide_" + Slug(runs[i].method, '_');
    gp += fmt::format(
        "{}'{}_force.csv' using 1:2 with lines title '{} thumb', "
        "'{}_force.csv' using 1:3 with lines title '{} index', "
        "'{}_force.csv' using 1:4 with lines title '{} push'",
        i ? ", " : "", slug, runs[i].method, slug, runs[i].method, slug, runs[i].method);
  }
  gp += "\nset title 'box x (m)'\nplot ";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    gp += fmt::format("{}'runs/slide_{}_box.csv' using 1:2 with lines title '{}'", i ? ", " : "",
                      Slug(runs[i].method, '_'), runs[i].method);
  }
  return gp + "\nunset multiplot\n";
}

// A slide run's row in grasp_slide.csv and the slide table and its summary["slide"] entry.
void AddSlideRow(const GraspRun& run, const SlideResult& r, Table* csv, Table* table,
                 nlohmann::json* summary) {
  csv->AddFormatted("{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.5f}", run.method,
                    run.physics_dt, r.mean_force[0], r.mean_force[1], r.sd_force[0], r.sd_force[1],
                    r.push_force, r.coulomb, r.carried, r.box_travel);
  table->Add({run.method, fmt::format("{} ms", run.physics_dt * 1e3),
              fmt::format("{:.3f}", r.mean_force[0]), fmt::format("{:.3f}", r.mean_force[1]),
              fmt::format("{:.3f}", r.sd_force[0]), fmt::format("{:.3f}", r.sd_force[1]),
              fmt::format("{:.3f}", r.push_force), fmt::format("{:.3f}", r.coulomb),
              fmt::format("{:.1f}", r.box_travel * 1e3)});
  (*summary)["slide"][run.method] = {{"physics_dt", run.physics_dt},
                                     {"mean_force_N", {r.mean_force[0], r.mean_force[1]}},
                                     {"sd_force_N", {r.sd_force[0], r.sd_force[1]}},
                                     {"push_N", r.push_force},
                                     {"coulomb_N", r.coulomb},
                                     {"carried_N", r.carried},
                                     {"box_travel_m", r.box_travel}};
}

}  // namespace

// The reference must drag the box with Coulomb's sliding force and carry it the fingers' travel;
// the local-dynamics methods at 20 ms must meet the slide bars against it. proxy-6dof and
// impulse are reported.
void RunGraspSlide(const std::filesystem::path& out, bool quiet, std::string* md, Checks* checks,
                   nlohmann::json* summary) {
  const std::vector<GraspRun> runs = GraspRuns();
  Table csv({"method", "physics_dt_s", "thumb_mean_N", "index_mean_N", "thumb_sd_N", "index_sd_N",
             "push_N", "coulomb_N", "carried_N", "box_travel_m"});
  Table table({"method", "physics dt", "thumb mean force (N)", "index mean force (N)",
               "thumb sd (N)", "index sd (N)", "push (N)", "μ (m g − carried) (N)",
               "box travel (mm)"});
  std::vector<SlideResult> results;
  for (const GraspRun& run : runs) {
    if (!quiet) std::cout << "grasp slide: " << run.method << "...\n";
    const SlideResult r = RunSlideCase(out, run);
    results.push_back(r);
    AddSlideRow(run, r, &csv, &table, summary);
  }
  const SlideResult& ref = results[0];
  const double push_error = ref.push_force / ref.coulomb - 1.0;
  checks->Add("slide_single_rate_push_is_coulomb", std::abs(push_error) <= 0.05, push_error, 0.05);
  const double lag = ref.box_travel - ref.fingers_travel;
  checks->Add("slide_single_rate_carries_the_box_m", std::abs(lag) <= 0.005, lag, 0.005);
  for (std::size_t i = 1; i < runs.size(); ++i) {
    const bool bars = MeetsSlideBars(results[i], ref);
    (*summary)["slide"][runs[i].method]["meets_bars"] = bars;
    if (!GraspChecked(runs[i])) continue;
    const std::string method = CheckName(runs[i].method);
    checks->Add("slide_" + method + "_meets_bars", bars);
    // Its own load on the floor may differ from the reference's (the fingers' vertical
    // friction is statically indeterminate), but the push must be Coulomb's for that load.
    const SlideResult& r = results[i];
    const double error = r.push_force / r.coulomb - 1.0;
    checks->Add("slide_" + method + "_push_is_coulomb", std::abs(error) <= 0.05, error, 0.05);
  }
  WriteText(out / "grasp_slide.csv", csv.Csv());
  Plot(out, "grasp_slide", SlideScript(runs), quiet);
  *md += "\n### A squeezed box pushed sideways (slide 1.1–1.8 s)\n\n" + table.Markdown();
}

}  // namespace mrh::experiments::internal
