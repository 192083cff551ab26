// SPDX-License-Identifier: Apache-2.0
// Experiment T4.1 (thesis §4.5.3, fig. 4.13, table 4.3): impulse delivered to a moving cube.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <vector>

#include "experiment_util.h"
#include "experiments_impl.h"
#include "mrh/engine/engine.h"
#include "mrh/report/report.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::experiments::internal {
namespace {

// The T4.1 parameters (SPEC §5): 60 kg at 0.017 m/s; an elastic bounce returns 2mv.
constexpr double kMass = 60.0;
constexpr double kSpeed = 0.017;
constexpr double kElasticImpulse = 2.0 * kMass * kSpeed;
// Acceptance (SPEC T4.1): single-rate within a few percent of the elastic bounce; the impulse
// method clearly larger (the thesis measured +60 %; "clearly" taken as more than +20 %).
constexpr double kSingleRateTolerance = 0.02;
constexpr double kImpulseMethodMinRatio = 1.2;

struct Published {
  const char* method;
  double impulse;  // N·s, thesis table 4.3
};
constexpr Published kThesis[] = {{"single-rate", 2.0}, {"impulse", 3.2}};

// Forwards everything to the CSV recorder and keeps the force on the cube (−f_d, eq. 4.12).
class ForceTap final : public engine::Recorder {
 public:
  explicit ForceTap(report::CsvRecorder* csv) : csv_(csv) {}
  void OnTick(const engine::TickRecord& tick) override {
    csv_->OnTick(tick);
    t.push_back(tick.t);
    f_cube.push_back(-tick.rendered_W.f.x());
  }
  void OnStep(const engine::StepRecord& step, const world::World& world) override {
    csv_->OnStep(step, world);
  }
  std::vector<double> t;
  std::vector<double> f_cube;

 private:
  report::CsvRecorder* csv_;
};

struct MethodResult {
  std::string method;
  std::vector<double> t, f_cube;
  double impulse = 0.0;       // N·s on the cube, from the engine's bookkeeping
  double contact_time = 0.0;  // s with a non-zero force
  double peak_force = 0.0;    // N
  double thesis = 0.0;
};

MethodResult RunMethod(const std::string& method, const std::filesystem::path& out, bool quiet) {
  const std::filesystem::path session_file =
      ScenesDir() / fmt::format("t4_1_{}.json", method == "single-rate" ? "single_rate" : method);
  const session::Session session = session::LoadSession(session_file);
  auto engine = session::MakeEngine(session);
  const std::filesystem::path dir = out / method;
  report::CsvRecorder csv(dir);
  ForceTap tap(&csv);
  const engine::RunStats stats = engine->Run(&tap);
  csv.Close();
  report::WriteSummary(dir, stats, session_file.string(), session.scene.string());
  std::string why;
  if (!report::PlotReport(dir, "T4.1 " + method, &why) && !quiet) {
    std::cerr << "mrh: warning: no plot for " << method << ": " << why << "\n";
  }
  MethodResult r;
  r.method = method;
  const int cube = engine->world().FindBody("cube");
  for (const engine::BodyImpulseTotal& total : stats.impulses) {
    if (total.body == cube) r.impulse = -total.linear.x();
  }
  for (std::size_t i = 0; i < tap.f_cube.size(); ++i) {
    r.peak_force = std::max(r.peak_force, std::abs(tap.f_cube[i]));
    if (tap.f_cube[i] != 0.0) r.contact_time += stats.haptic_dt;
  }
  for (const Published& p : kThesis) {
    if (method == p.method) r.thesis = p.impulse;
  }
  r.t = std::move(tap.t);
  r.f_cube = std::move(tap.f_cube);
  return r;
}

void WriteForceTime(const std::filesystem::path& out, const std::vector<MethodResult>& results) {
  std::string csv = "t";
  for (const MethodResult& r : results) csv += "," + r.method;
  csv += "\n";
  const std::size_t rows = results.front().t.size();
  for (std::size_t i = 0; i < rows; ++i) {
    csv += fmt::format("{}", results.front().t[i]);
    for (const MethodResult& r : results) {
      csv += fmt::format(",{}", i < r.f_cube.size() ? -r.f_cube[i] : 0.0);
    }
    csv += "\n";
  }
  WriteText(out / "force_time.csv", csv);
  std::string plot = fmt::format(
      "# Thesis fig. 4.13: force on the cube vs time. Re-run with: gnuplot force_time.gp\n"
      "set terminal pngcairo size 1000,600 enhanced font ',11'\n"
      "set output 'force_time.png'\nset datafile separator ','\nset grid\n"
      "set title 'T4.1: 60 kg cube at 0.017 m/s against a fixed pointer (k = 1000 N/m)'\n"
      "set xlabel 't (s)'\nset ylabel 'force on the pointer f_x (N)'\nset key top left\n"
      "plot ");
  for (std::size_t i = 0; i < results.size(); ++i) {
    plot += fmt::format("{}'force_time.csv' using 1:{} with lines lw 2 title '{}'",
                        i == 0 ? "" : ", ", i + 2, results[i].method);
  }
  WriteText(out / "force_time.gp", plot + "\n");
}

}  // namespace

int RunT41(const std::filesystem::path& out, bool quiet) {
  std::filesystem::create_directories(out);
  std::vector<MethodResult> results;
  for (const char* method : {"single-rate", "impulse"}) {
    if (!quiet) std::cout << "t4.1: running " << method << "...\n";
    results.push_back(RunMethod(method, out, quiet));
  }
  WriteForceTime(out, results);
  std::string why;
  if (!report::RunGnuplotScript(out, "force_time.gp", "force_time.png", &why) && !quiet) {
    std::cerr << "mrh: warning: force_time.png not drawn: " << why << "\n";
  }

  const double single = results[0].impulse;
  const bool single_ok = std::abs(single - kElasticImpulse) <= kSingleRateTolerance * kElasticImpulse;
  const bool impulse_ok = results[1].impulse > kImpulseMethodMinRatio * single;

  std::string table =
      "method,impulse_Ns,elastic_2mv_Ns,ratio_to_single_rate,thesis_Ns,contact_s,peak_force_N\n";
  std::string md = "| method | impulse (N·s) | ratio to single-rate | thesis (N·s) | contact (s) | "
                   "peak force (N) |\n|---|---|---|---|---|---|\n";
  nlohmann::json summary;
  for (const MethodResult& r : results) {
    table += fmt::format("{},{:.6f},{:.6f},{:.4f},{},{:.3f},{:.4f}\n", r.method, r.impulse,
                         kElasticImpulse, r.impulse / single, r.thesis, r.contact_time,
                         r.peak_force);
    md += fmt::format("| {} | {:.4f} | {:.3f} | {:.1f} | {:.3f} | {:.3f} |\n", r.method, r.impulse,
                      r.impulse / single, r.thesis, r.contact_time, r.peak_force);
    summary["methods"][r.method] = {{"impulse_Ns", r.impulse}, {"contact_s", r.contact_time},
                                    {"peak_force_N", r.peak_force}, {"thesis_Ns", r.thesis}};
  }
  WriteText(out / "impulse_table.csv", table);
  WriteText(out / "impulse_table.md", md);
  summary["experiment"] = "t4.1";
  summary["machine"] = MachineTag();
  summary["elastic_2mv_Ns"] = kElasticImpulse;
  summary["checks"] = {
      {"single_rate_within_2_percent_of_2mv", single_ok},
      {"impulse_method_above_1.2x_single_rate", impulse_ok}};
  WriteText(out / "summary.json", summary.dump(2) + "\n");
  if (!quiet) {
    std::cout << md << fmt::format("elastic bounce 2mv = {:.3f} N·s\n", kElasticImpulse)
              << fmt::format("check single-rate within 2 % of 2mv: {}\n", single_ok ? "pass" : "FAIL")
              << fmt::format("check impulse method > 1.2 x single-rate: {}\n",
                             impulse_ok ? "pass" : "FAIL")
              << "results: " << std::filesystem::absolute(out).string() << "\n";
  }
  return single_ok && impulse_ok ? 0 : 1;
}

}  // namespace mrh::experiments::internal
