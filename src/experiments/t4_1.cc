// SPDX-License-Identifier: Apache-2.0
// Experiment T4.1 (thesis §4.5.3, fig. 4.13, table 4.3): impulse delivered to a moving cube.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>
#include <tuple>
#include <vector>

#include "experiment_table.h"
#include "experiment_util.h"
#include "experiments_impl.h"
#include "mrh/core/error.h"
#include "mrh/engine/engine.h"
#include "mrh/engine/method.h"
#include "mrh/ir/snapshot.h"
#include "mrh/report/report.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"

namespace mrh::experiments::internal {
namespace {

// The T4.1 parameters (thesis §4.5.3): 60 kg at 0.017 m/s; an elastic bounce returns 2mv.
constexpr double kMass = 60.0;
constexpr double kSpeed = 0.017;
// Gap between the cube's face and the sphere at t = 0 in scenes/t4_1.xml (m).
constexpr double kGap = 0.005;
// Acceptance (T4.1): single-rate within 2 % of the elastic bounce; local-dynamics within
// 2 % of single-rate (the thesis' table 4.3 shows them equal to its 2 significant digits); the
// impulse method clearly larger: the thesis measured +60 %, we require at least a third of that
// excess (+20 %), since the overshoot grows with the step's share of the contact time, which the
// thesis' unreported sizes fix differently.
constexpr double kSingleRateTolerance = 0.02;
constexpr double kLocalDynamicsTolerance = 0.02;
constexpr double kImpulseMethodMinRatio = 1.2;
// The free cube's measured accelerance must be 1/m to rounding (MuJoCo integrates a free
// slide-jointed body exactly: Δv = F·Δt/m).
constexpr double kAccelTolerance = 1e-9;

struct Published {
  const char* method;
  double impulse;  // N·s, thesis table 4.3
};

constexpr Published kThesis[] = {{"single-rate", 2.0}, {"impulse", 3.2}, {"local-dynamics", 2.0}};

// Sweep of T4.1's two parameters (mass, speed) around the thesis' point.
constexpr double kSweepMasses[] = {15.0, 30.0, 60.0, 120.0, 240.0};
constexpr double kSweepSpeeds[] = {0.005, 0.01, 0.017, 0.05, 0.1};

struct Case {
  double mass = kMass;    // kg
  double speed = kSpeed;  // m/s

  double elastic() const { return 2.0 * mass * speed; }
};

// Keeps the force on the cube (−f_d, eq. 4.12) and optionally forwards to a CSV recorder.
class ForceTap final : public physics::Recorder {
 public:
  explicit ForceTap(report::CsvRecorder* csv) : csv_(csv) {}

  void OnTick(const ir::TickRecord& tick) override {
    if (csv_ != nullptr) csv_->OnTick(tick);
    t.push_back(tick.t);
    f_cube.push_back(-tick.rendered_W.f.x());
  }

  void OnStep(const physics::StepRecord& step, const world::World& world) override {
    if (csv_ != nullptr) csv_->OnStep(step, world);
  }

  std::vector<double> t;
  std::vector<double> f_cube;

 private:
  report::CsvRecorder* csv_;
};

struct MethodResult {
  std::string method;
  Case c;
  std::vector<double> t, f_cube;
  double impulse = 0.0;       // N·s on the cube, from the engine's bookkeeping
  double momentum = 0.0;      // N·s, m·Δv of the cube in the global world at the end
  double contact_time = 0.0;  // s with a non-zero force
  double peak_force = 0.0;    // N
  bool ended = false;         // contact over before the run ended
  double thesis = 0.0;
};

// The T4.1 session for one method and case. Off-centre cases get a generated copy of the scene
// (mass and keyframe speed replaced) and a duration covering approach, contact and margin.
session::Session CaseSession(const std::string& method, const Case& c,
                             const std::filesystem::path& dir) {
  session::Session s = session::LoadSession(ScenesDir() / "t4_1_impulse.json");
  s.engine.method = method;
  // T4.1 reproduces the thesis' table: local-dynamics with the thesis' perturbation model.
  s.engine.rendering.local_model = settings::LocalModel::kPerturbation;
  if (c.mass == kMass && c.speed == kSpeed) return s;
  const std::filesystem::path file = ScenesDir() / "t4_1.xml";
  constexpr std::string_view kWhy =
      "the T4.1 driver edits it to sweep mass and speed, keep it in the scene";
  std::string xml =
      ReplaceOnce(ReadText(file), "mass=\"60\"", fmt::format("mass=\"{}\"", c.mass), file, kWhy);
  xml = ReplaceOnce(xml, "qvel=\"0.017 0 0\"", fmt::format("qvel=\"{} 0 0\"", c.speed), file, kWhy);
  std::filesystem::create_directories(dir);
  s.scene = dir / fmt::format("t4_1_m{}_v{}.xml", c.mass, c.speed);
  WriteText(s.scene, xml);
  // Contact lasts π·sqrt(m/k) for an ideal spring; allow 2.5 times that for the slower methods.
  const double contact = M_PI * std::sqrt(c.mass / s.engine.rendering.stiffness);
  s.engine.duration = std::ceil((kGap / c.speed + 2.5 * contact + 0.1) * 10.0) / 10.0;
  return s;
}

MethodResult RunCase(const session::Session& session, const Case& c,
                     const std::filesystem::path& dir, bool quiet) {
  auto engine = session::MakeEngine(session);
  std::optional<report::CsvRecorder> csv;
  if (!dir.empty()) csv.emplace(dir);
  ForceTap tap(csv ? &*csv : nullptr);
  const engine::RunStats stats = engine->Run(&tap);
  std::string why;
  if (csv) {
    csv->Close();
    report::WriteSummary(dir, stats, session.file.string(), session.scene.string());
    // Every T4.1 method renders a 3-DOF point force: no torque or orientation panels.
    if (!report::PlotReport(dir, "T4.1 " + session.engine.method, &why,
                            report::ReportOptions{.six_dof = false}) &&
        !quiet) {
      std::cerr << "mrh: warning: no plot for " << session.engine.method << ": " << why << "\n";
    }
  }
  MethodResult r;
  r.method = session.engine.method;
  r.c = c;
  const int cube = engine->world().FindBody("cube");
  for (const physics::BodyImpulseTotal& total : stats.impulses) {
    if (total.body == cube) r.impulse = -total.linear.x();
  }
  r.momentum = c.mass * (c.speed - engine->world().body_state(cube).V_WCm.v.x());
  for (std::size_t i = 0; i < tap.f_cube.size(); ++i) {
    r.peak_force = std::max(r.peak_force, std::abs(tap.f_cube[i]));
    if (tap.f_cube[i] != 0.0) r.contact_time += stats.haptic_dt;
  }
  r.ended = r.contact_time > 0.0 && !tap.f_cube.empty() && tap.f_cube.back() == 0.0;
  for (const Published& p : kThesis) {
    if (r.method == p.method) r.thesis = p.impulse;
  }
  r.t = std::move(tap.t);
  r.f_cube = std::move(tap.f_cube);
  return r;
}

// The accelerance local-dynamics measures for the free cube at t = 0, through the public Method
// interface: one physics step from the initial state, read the snapshot's A.
ir::Mat63 MeasureAccelerance() {
  session::Session s = CaseSession("local-dynamics", Case{}, {});  // the thesis' A
  world::World world = session::LoadWorld(s);
  world.set_timestep(s.engine.physics_dt);
  physics::MethodContext context{.world = &world,
                                 .settings = &s.engine,
                                 .pointer_body = world.pointer_body(),
                                 .pointer_radius = s.engine.pointer.radius};
  auto method = engine::MakeMethod("local-dynamics", context);
  ir::HapticReport report;
  report.X_WP = s.device.calibration.ToWorld(s.device.pose);
  auto snapshot = std::make_unique<ir::PhysicsSnapshot>();
  method.physics->PhysicsStart(report, snapshot.get());
  method.physics->PhysicsStep(report, snapshot.get());
  const int cube = world.FindBody("cube");
  for (const ir::BodyMotion& body : snapshot->bodies) {
    if (body.body == cube && body.has_dynamics) return body.A;
  }
  throw RuntimeError("t4.1: local-dynamics sent no accelerance for the cube in its first step");
}

// force_time.csv (the force on the cube per tick, a column per method) and its plot.
void WriteForceTime(const std::filesystem::path& out, const std::vector<MethodResult>& results,
                    bool quiet) {
  std::vector<std::string> columns = {"t"};
  for (const MethodResult& r : results) columns.push_back(r.method);
  Table csv(columns);
  const std::size_t rows = results.front().t.size();
  for (std::size_t i = 0; i < rows; ++i) {
    std::vector<std::string> row = {fmt::format("{}", results.front().t[i])};
    for (const MethodResult& r : results) {
      row.push_back(fmt::format("{}", i < r.f_cube.size() ? -r.f_cube[i] : 0.0));
    }
    csv.Add(std::move(row));
  }
  WriteText(out / "force_time.csv", csv.Csv());
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
  Plot(out, "force_time", plot + "\n", quiet);
}

// Writes one sweep panel's data: x, then the error of each method (columns in `methods` order).
void WritePanel(const std::filesystem::path& file, const std::vector<std::string>& methods,
                const std::vector<std::vector<double>>& errors, const double* xs, std::size_t n) {
  std::vector<std::string> columns = {"x"};
  columns.insert(columns.end(), methods.begin(), methods.end());
  Table csv(columns);
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<std::string> row = {fmt::format("{}", xs[i])};
    for (const std::vector<double>& e : errors) row.push_back(fmt::format("{:.6f}", e[i]));
    csv.Add(std::move(row));
  }
  WriteText(file, csv.Csv());
}

std::string SweepScript(const std::vector<std::string>& methods) {
  std::string plot =
      "# Impulse error (J - 2mv)/2mv per method. Re-run with: gnuplot sweep.gp\n"
      "set terminal pngcairo size 1200,500 enhanced font ',11'\nset output 'sweep.png'\n"
      "set datafile separator ','\nset grid\nset multiplot layout 1,2\nset logscale x\n"
      "set ylabel 'impulse error (J - 2mv)/2mv'\nset key top right\n";
  for (const auto& [file, xlabel, title] :
       {std::tuple{"sweep_vs_mass.csv", "cube mass (kg)", "initial speed 0.017 m/s"},
        std::tuple{"sweep_vs_speed.csv", "initial speed (m/s)", "cube mass 60 kg"}}) {
    plot += fmt::format("set xlabel '{}'\nset title '{}'\nplot ", xlabel, title);
    for (std::size_t i = 0; i < methods.size(); ++i) {
      plot += fmt::format("{}'{}' using 1:{} with linespoints lw 2 title '{}'", i == 0 ? "" : ", ",
                          file, i + 2, methods[i]);
    }
    plot += "\n";
  }
  return plot + "unset multiplot\n";
}

// The impulse error (J − 2mv)/2mv of every method over the mass × speed grid (sweep.csv), and
// its plot: error vs mass at the thesis' speed and error vs speed at the thesis' mass.
nlohmann::json RunSweep(const std::filesystem::path& out, const std::vector<std::string>& methods,
                        bool quiet) {
  constexpr std::size_t kNm = std::size(kSweepMasses), kNv = std::size(kSweepSpeeds);
  Table csv({"method", "mass_kg", "speed_mps", "elastic_2mv_Ns", "impulse_Ns", "error",
             "momentum_Ns", "ended"});
  std::vector<std::vector<double>> vs_mass, vs_speed;
  nlohmann::json worst;
  for (const std::string& method : methods) {
    if (!quiet) std::cout << "t4.1: sweeping " << method << "...\n";
    vs_mass.emplace_back(kNm, 0.0);
    vs_speed.emplace_back(kNv, 0.0);
    double max_error = 0.0;
    for (std::size_t i = 0; i < kNm; ++i) {
      for (std::size_t j = 0; j < kNv; ++j) {
        const Case c{kSweepMasses[i], kSweepSpeeds[j]};
        const MethodResult r = RunCase(CaseSession(method, c, out / "sweep"), c, {}, quiet);
        const double error = (r.impulse - c.elastic()) / c.elastic();
        max_error = std::max(max_error, std::abs(error));
        if (c.speed == kSpeed) vs_mass.back()[i] = error;
        if (c.mass == kMass) vs_speed.back()[j] = error;
        csv.AddFormatted("{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{}", method, c.mass, c.speed,
                         c.elastic(), r.impulse, error, r.momentum, r.ended ? 1 : 0);
      }
    }
    worst[method] = max_error;
  }
  WriteText(out / "sweep.csv", csv.Csv());
  WritePanel(out / "sweep_vs_mass.csv", methods, vs_mass, kSweepMasses, kNm);
  WritePanel(out / "sweep_vs_speed.csv", methods, vs_speed, kSweepSpeeds, kNv);
  Plot(out, "sweep", SweepScript(methods), quiet);
  return worst;
}

const MethodResult* Find(const std::vector<MethodResult>& results, const char* method) {
  for (const MethodResult& r : results) {
    if (r.method == method) return &r;
  }
  return nullptr;
}

// Table 4.3: impulse per method, ratio to single-rate (or to 2mv without single-rate).
void WriteT41Table(const std::filesystem::path& out, const std::vector<MethodResult>& results,
                   nlohmann::json* summary) {
  const MethodResult* single = Find(results, "single-rate");
  const double reference = single != nullptr ? single->impulse : Case{}.elastic();
  Table table({"method", "impulse_Ns", "momentum_Ns", "elastic_2mv_Ns", "ratio_to_single_rate",
               "thesis_Ns", "contact_s", "peak_force_N"});
  Table md({"method", "impulse (N·s)", "ratio to single-rate", "thesis (N·s)", "contact (s)",
            "peak force (N)"});
  for (const MethodResult& r : results) {
    table.AddFormatted("{},{:.6f},{:.6f},{:.6f},{:.4f},{},{:.3f},{:.4f}", r.method, r.impulse,
                       r.momentum, Case{}.elastic(), r.impulse / reference, r.thesis,
                       r.contact_time, r.peak_force);
    md.Add({r.method, fmt::format("{:.4f}", r.impulse),
            fmt::format("{:.3f}", r.impulse / reference), fmt::format("{:.1f}", r.thesis),
            fmt::format("{:.3f}", r.contact_time), fmt::format("{:.3f}", r.peak_force)});
    (*summary)["methods"][r.method] = {{"impulse_Ns", r.impulse},
                                       {"momentum_Ns", r.momentum},
                                       {"contact_s", r.contact_time},
                                       {"peak_force_N", r.peak_force},
                                       {"thesis_Ns", r.thesis}};
  }
  WriteText(out / "impulse_table.csv", table.Csv());
  WriteText(out / "impulse_table.md", md.Markdown());
  (*summary)["impulse_table_md"] = md.Markdown();
}

// The free cube's accelerance as local-dynamics measures it against I/m (summary numbers).
bool AccelerancePasses(nlohmann::json* summary) {
  const ir::Mat63 A = MeasureAccelerance();
  const Mat3 expected = Mat3::Identity() / kMass;
  const double error = (A.topRows<3>() - expected).cwiseAbs().maxCoeff() * kMass;
  (*summary)["accelerance_linear_diag_per_kg"] = {A(0, 0), A(1, 1), A(2, 2)};
  (*summary)["accelerance_angular_max"] = A.bottomRows<3>().cwiseAbs().maxCoeff();
  return error <= kAccelTolerance;
}

// The checks of T4.1 on whichever methods ran; writes summary.json, returns the exit code.
int FinishT41(const std::filesystem::path& out, const std::vector<MethodResult>& results,
              bool quiet, nlohmann::json* summary) {
  Checks checks;
  const MethodResult* single = Find(results, "single-rate");
  const MethodResult* impulse = Find(results, "impulse");
  const MethodResult* local = Find(results, "local-dynamics");
  if (single != nullptr) {
    checks.Add(
        "single_rate_within_2_percent_of_2mv",
        std::abs(single->impulse - Case{}.elastic()) <= kSingleRateTolerance * Case{}.elastic());
  }
  if (single != nullptr && impulse != nullptr) {
    checks.Add("impulse_method_above_1.2x_single_rate",
               impulse->impulse > kImpulseMethodMinRatio * single->impulse);
  }
  if (single != nullptr && local != nullptr) {
    checks.Add(
        "local_dynamics_within_2_percent_of_single_rate",
        std::abs(local->impulse - single->impulse) <= kLocalDynamicsTolerance * single->impulse);
  }
  if (local != nullptr) {
    checks.Add("free_cube_accelerance_is_identity_over_60kg", AccelerancePasses(summary));
  }
  if (!quiet) {
    std::cout << (*summary)["impulse_table_md"].get<std::string>()
              << fmt::format("elastic bounce 2mv = {:.3f} N·s\n", Case{}.elastic());
  }
  return FinishExperiment(out, std::move(*summary), checks, quiet);
}

}  // namespace

int RunT41(const std::filesystem::path& out, bool quiet) {
  return RunT41(out, quiet, T41Options{});
}

int RunT41(const std::filesystem::path& out, bool quiet, const T41Options& options) {
  std::filesystem::create_directories(out);
  std::vector<MethodResult> results;
  for (const std::string& method : options.methods) {
    if (!quiet) std::cout << "t4.1: running " << method << "...\n";
    results.push_back(RunCase(CaseSession(method, Case{}, {}), Case{}, out / method, quiet));
  }
  WriteForceTime(out, results, quiet);
  nlohmann::json summary;
  summary["experiment"] = "t4.1";
  summary["machine"] = MachineTag();
  summary["elastic_2mv_Ns"] = Case{}.elastic();
  WriteT41Table(out, results, &summary);
  if (options.sweep) summary["sweep_max_abs_error"] = RunSweep(out, options.methods, quiet);
  return FinishT41(out, results, quiet, &summary);
}

}  // namespace mrh::experiments::internal
