// SPDX-License-Identifier: Apache-2.0
// The grasp experiment's two-hands case: two scripted hands push two boxes apart across a floor
// with friction, each hand its own box, together and each alone.
#include <fmt/format.h>

#include <algorithm>
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

constexpr double kSpeed = 0.1;         // m/s, each hand away from the other
constexpr double kHeight = 0.05;       // m, the boxes' mid-height
constexpr double kRadius = 0.015;      // m, the scene's pointers
constexpr double kStiffness = 2000.0;  // N/m
constexpr double kDamping = 5.0;       // N·s/m
constexpr double kMu = 0.5;            // the scene's box–floor friction
constexpr double kGravity = 9.81;      // m/s², the scene's
// Each hand touches its box at 1 s; by 2 s the box slides steadily at the hand's speed.
constexpr double kFrom = 2.0;  // s
constexpr double kTo = 4.0;    // s, also the run's end

struct Hand {
  const char* body;
  const char* box;
  double x0;         // m, start
  double direction;  // ±1 along x
};

constexpr Hand kHands[2] = {{"left_hand", "left_box", -0.035, -1.0},
                            {"right_hand", "right_box", 0.035, 1.0}};

session::Session MakeSession(const GraspRun& run, const std::vector<int>& hands) {
  nlohmann::json j;
  j["scene"] = "two_hands_push.xml";
  j["method"] = run.method;
  j["physics_dt"] = run.physics_dt;
  j["haptic_dt"] = 0.001;
  j["duration"] = kTo;
  j["rendering"] = {{"stiffness", kStiffness}, {"damping", kDamping}};
  j["pointers"] = nlohmann::json::array();
  for (const int i : hands) {
    const Hand& h = kHands[i];
    const double x1 = h.x0 + h.direction * kSpeed * kTo;
    const nlohmann::json frames = {{0.0, h.x0, 0.0, kHeight, 1, 0, 0, 0},
                                   {kTo, x1, 0.0, kHeight, 1, 0, 0, 0}};
    j["pointers"].push_back({{"body", h.body},
                             {"radius", kRadius},
                             {"device", {{"type", "scripted"}, {"keyframes", frames}}}});
  }
  return session::ParseSession(j.dump(), ScenesDir(), {},
                               fmt::format("grasp two hands ({} at {} ms, {} hand(s))", run.method,
                                           run.physics_dt * 1e3, hands.size()));
}

std::string RunSlug(const GraspRun& run, const std::vector<int>& hands) {
  std::string slug = "hands_" + Slug(run.method, '_');
  if (hands.size() == 1) slug += hands[0] == 0 ? "_left_alone" : "_right_alone";
  return slug;
}

void WriteRun(const std::filesystem::path& dir, const std::string& slug, const PointerTap& tap,
              const std::vector<int>& hands) {
  Table f({"t", "left_N", "right_N"});
  const auto& a = tap.forces(0);
  const auto& b = tap.forces(1);
  for (std::size_t k = 0; k < a.size(); ++k) {
    // A run with one hand has one pointer: its forces are pointer 0's.
    const double left = hands[0] == 0 ? a[k].f.norm() : 0.0;
    const double right = hands.size() == 2 ? (k < b.size() ? b[k].f.norm() : 0.0)
                                           : (hands[0] == 1 ? a[k].f.norm() : 0.0);
    f.AddFormatted("{:.3f},{:.5f},{:.5f}", a[k].t, left, right);
  }
  WriteText(dir / (slug + "_force.csv"), f.Csv());
  Table x({"t", "left_box_x", "right_box_x"});
  for (const PointerTap::Step& s : tap.steps()) {
    x.AddFormatted("{:.3f},{:.6f},{:.6f}", s.t, s.p[0].x(), s.p[1].x());
  }
  WriteText(dir / (slug + "_box.csv"), x.Csv());
}

}  // namespace

HandsResult RunHandsCase(const std::filesystem::path& out, const GraspRun& run,
                         const std::vector<int>& hands) {
  auto engine = session::MakeEngine(MakeSession(run, hands));
  PointerTap tap({kHands[0].box, kHands[1].box});
  engine->Run(&tap);
  if (!out.empty()) {
    std::filesystem::create_directories(out / "runs");
    WriteRun(out / "runs", RunSlug(run, hands), tap, hands);
  }
  HandsResult r;
  const std::vector<PointerTap::Step>& steps = tap.steps();
  for (std::size_t k = 0; k < hands.size(); ++k) {
    const int i = hands[k];
    const ForceStats s = WindowForce(tap.forces(static_cast<int>(k)), kFrom, kTo);
    r.mean_force[i] = s.mean_norm;
    r.sd_force[i] = s.sd_norm;
  }
  for (int i = 0; i < 2; ++i) {
    r.coulomb[i] = kMu * tap.mass(i) * kGravity;
    if (!steps.empty()) {
      r.travel[i] = kHands[i].direction * (steps.back().p[i].x() - steps.front().p[i].x());
    }
  }
  return r;
}

namespace {

std::string HandsScript(const std::vector<GraspRun>& runs) {
  std::string gp =
      "# grasp, two hands: each hand's |f| and each box's x per method, both hands pushing\n"
      "# (runs/hands_*_alone_*.csv: each hand alone). gnuplot grasp_hands.gp\n"
      "set terminal pngcairo size 1200,700 enhanced font ',9'\nset output 'grasp_hands.png'\n"
      "set datafile separator ','\nset grid\nset key bottom right\nset multiplot layout 2,1\n"
      "set title 'hand force |f| (N); mu m g = 2.45 N (left), 1.47 N (right)'\n"
      "set xlabel 't (s)'\nset yrange [0:4]\nplot ";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string slug = "runs/hands_" + Slug(runs[i].method, '_');
    gp += fmt::format(
        "{}'{}_force.csv' using 1:2 with lines title '{} left', "
        "'{}_force.csv' using 1:3 with lines title '{} right'",
        i ? ", " : "", slug, runs[i].method, slug, runs[i].method);
  }
  gp += "\nset title 'box x (m)'\nset yrange [*:*]\nplot ";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string slug = "runs/hands_" + Slug(runs[i].method, '_');
    gp += fmt::format(
        "{}'{}_box.csv' using 1:2 with lines title '{} left box', "
        "'{}_box.csv' using 1:3 with lines title '{} right box'",
        i ? ", " : "", slug, runs[i].method, slug, runs[i].method);
  }
  return gp + "\nunset multiplot\n";
}

}  // namespace

// The acceptance bar for two hands: each hand feels its own box's Coulomb force μ m g within 5 %,
// undisturbed by the other hand (its force alone within 5 %). Checked for the reference and for
// the local-dynamics methods; proxy-6dof and impulse are reported.
void RunGraspHands(const std::filesystem::path& out, bool quiet, std::string* md, Checks* checks,
                   nlohmann::json* summary) {
  const std::vector<GraspRun> runs = GraspRuns();
  const char* names[2] = {"left", "right"};
  Table csv({"method", "physics_dt_s", "hand", "mean_N", "sd_N", "mu_m_g_N", "vs_mu_m_g",
             "alone_mean_N", "vs_alone", "box_travel_m"});
  Table table({"method", "physics dt", "hand", "mean force (N)", "sd (N)", "μ m g (N)", "vs μ m g",
               "alone (N)", "vs alone", "box travel (m)"});
  for (const GraspRun& run : runs) {
    if (!quiet) std::cout << "grasp two hands: " << run.method << "...\n";
    const HandsResult both = RunHandsCase(out, run, {0, 1});
    const bool checked = run.method == "single-rate" || GraspChecked(run);
    for (int i = 0; i < 2; ++i) {
      const HandsResult alone = RunHandsCase(out, run, {i});
      const double vs_coulomb = both.mean_force[i] / both.coulomb[i] - 1.0;
      const double vs_alone = both.mean_force[i] / alone.mean_force[i] - 1.0;
      csv.AddFormatted("{},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}", run.method,
                       run.physics_dt, names[i], both.mean_force[i], both.sd_force[i],
                       both.coulomb[i], vs_coulomb, alone.mean_force[i], vs_alone, both.travel[i]);
      table.Add({run.method, fmt::format("{} ms", run.physics_dt * 1e3), names[i],
                 fmt::format("{:.3f}", both.mean_force[i]), fmt::format("{:.3f}", both.sd_force[i]),
                 fmt::format("{:.3f}", both.coulomb[i]), fmt::format("{:+.2f} %", 100 * vs_coulomb),
                 fmt::format("{:.3f}", alone.mean_force[i]),
                 fmt::format("{:+.2f} %", 100 * vs_alone), fmt::format("{:.4f}", both.travel[i])});
      (*summary)["hands"][run.method][names[i]] = {
          {"physics_dt", run.physics_dt},   {"mean_force_N", both.mean_force[i]},
          {"sd_force_N", both.sd_force[i]}, {"mu_m_g_N", both.coulomb[i]},
          {"vs_mu_m_g", vs_coulomb},        {"alone_mean_force_N", alone.mean_force[i]},
          {"vs_alone", vs_alone},           {"box_travel_m", both.travel[i]}};
      if (!checked) continue;
      const std::string prefix = fmt::format("hands_{}_{}", CheckName(run.method), names[i]);
      checks->Add(prefix + "_feels_mu_m_g", std::abs(vs_coulomb) <= 0.05, vs_coulomb, 0.05);
      checks->Add(prefix + "_as_alone", std::abs(vs_alone) <= 0.05, vs_alone, 0.05);
    }
  }
  WriteText(out / "grasp_hands.csv", csv.Csv());
  Plot(out, "grasp_hands", HandsScript(runs), quiet);
  *md += "\n### Two hands push two boxes apart (steady slide, 2–4 s)\n\n" + table.Markdown();
}

}  // namespace mrh::experiments::internal
