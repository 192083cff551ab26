// SPDX-License-Identifier: Apache-2.0
// `mrh run`: runs a session and writes its CSV traces, summary.json and report.png.
#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "commands.h"
#include "mrh/device/device.h"
#include "mrh/engine/engine.h"
#include "mrh/report/report.h"
#include "mrh/session/session.h"
#include "mrh/world/world.h"
#include "progress_bar.h"
#include "servo_run.h"

namespace mrh::cli {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRunFooter = R"(Output (in --out, default out/<session stem>-<method>):
  ticks.csv     pointer pose and displayed wrench, one row per haptic tick
  bodies.csv    each moving body per physics step: body frame pose (x..qz), COM velocity
                (vx..wz) and COM position (cx,cy,cz)
  steps.csv     physics step timing, contacts, neighbors, solver iterations
  summary.json  rates, jitter, max force, impulses per body, faults, warnings
  report.png    force (clamping and contact loss marked), torque and orientation (6-DOF
                methods), pointer, and each body's travel, on one time axis (gnuplot;
                report.gp re-draws it)

Examples:
  mrh run session.json
  mrh run session.json --method single-rate --out out/baseline
  mrh run session.json --mode realtime --duration 5 --progress
  mrh run session.json --set rendering.stiffness=2000 --set physics_dt=0.02
)";

// CLI11's PositiveNumber would print DBL_MAX in full in its message; this one says what to give.
std::string CheckPositive(std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !std::isfinite(value) || value <= 0.0) {
    return fmt::format("expected a number of seconds > 0, got '{}'", text);
  }
  return {};
}

// The flags --mode/--method/--duration are session overrides applied after the --set ones, so
// the dedicated flag wins when both name the same key.
std::vector<std::string> Overrides(const RunOptions& o) {
  std::vector<std::string> overrides = o.sets;
  if (!o.mode.empty()) overrides.push_back("mode=" + o.mode);
  if (!o.method.empty()) overrides.push_back("method=" + o.method);
  if (o.duration) overrides.push_back(fmt::format("duration={}", *o.duration));
  return overrides;
}

fs::path OutputDir(const RunOptions& o, const session::Session& s) {
  const fs::path out =
      o.out.empty() ? fs::path("out") / (o.session.stem().string() + "-" + s.engine.method) : o.out;
  return fs::absolute(out).lexically_normal();
}

void PrintSummary(const engine::RunStats& s) {
  fmt::print("method:    {} ({}, physics {} ms, haptic {} ms)\n", s.method,
             settings::ModeName(s.mode), s.physics_dt * 1e3, s.haptic_dt * 1e3);
  fmt::print("ran:       {} ticks, {} steps, {:.3f} s simulated in {:.3f} s wall\n", s.ticks,
             s.steps, s.sim_time, s.wall_time);
  fmt::print("rates:     haptic {:.1f} Hz, physics {:.1f} Hz\n", s.haptic_rate_hz,
             s.physics_rate_hz);
  if (s.mode == settings::Mode::kRealtime) {
    fmt::print(
        "timing:    {} overruns, jitter p50 {:.1f} / p99 {:.1f} / max {:.1f} us, "
        "step p99 {:.2f} ms{}\n",
        s.overruns, s.jitter_p50_us, s.jitter_p99_us, s.jitter_max_us, s.step_ms_p99,
        s.realtime_priority ? "" : " (no real-time priority)");
  }
  fmt::print("max:       force {:.4g} N, torque {:.4g} N m\n", s.max_force, s.max_torque);
  for (const physics::BodyImpulseTotal& impulse : s.impulses) {
    fmt::print("impulse:   {:<16} |J| = {:.4g} N s  ({:.4g}, {:.4g}, {:.4g})\n",
               impulse.name.empty() ? fmt::format("body{}", impulse.body) : impulse.name,
               impulse.linear.norm(), impulse.linear.x(), impulse.linear.y(), impulse.linear.z());
  }
  const std::int64_t faults = s.fault_nonfinite_wrench + s.fault_nonfinite_device +
                              s.watchdog_ticks + s.dropped_tick_records + s.dropped_reports;
  if (faults > 0 || s.force_clamped > 0 || s.torque_clamped > 0) {
    fmt::print("faults:    {} non-finite, {} watchdog, {} dropped, {}/{} clamped (force/torque)\n",
               s.fault_nonfinite_wrench + s.fault_nonfinite_device, s.watchdog_ticks,
               s.dropped_tick_records + s.dropped_reports, s.force_clamped, s.torque_clamped);
  }
}

// What a real or network device counted itself (vendor errors, dropped torque, bad packets).
void PrintDeviceFaults(const device::Device& device) {
  const device::DeviceCounters c = device.counters();
  if (c.poses_received > 0 || c.wrenches_sent > 0) {
    fmt::print("device:    {} poses received, {} wrenches sent\n", c.poses_received,
               c.wrenches_sent);
  }
  if (c.vendor_errors > 0) {
    fmt::print(stderr, "mrh: warning: device: {} vendor errors (last: {})\n", c.vendor_errors,
               device.last_error());
  }
  if (c.torque_dropped > 0) {
    fmt::print(stderr, "mrh: warning: device: torque dropped on {} ticks (3-DOF force output)\n",
               c.torque_dropped);
  }
  if (c.packets_malformed > 0) {
    fmt::print(stderr, "mrh: warning: device: {} malformed or foreign packets dropped\n",
               c.packets_malformed);
  }
  if (c.pose_timeouts > 0) {
    fmt::print(stderr, "mrh: warning: device: no pose for device.timeout on {} ticks (faded)\n",
               c.pose_timeouts);
  }
}

}  // namespace

CLI::App* AddRunCommand(CLI::App& app, RunOptions* o) {
  CLI::App* run = app.add_subcommand(
      "run",
      "Run a session: simulate, render haptics, and write CSV traces, summary.json and "
      "report.png");
  run->add_option("SESSION", o->session, "Session file (JSON)")
      ->required()
      ->check(CLI::ExistingFile);
  run->add_option("--out,-o", o->out, "Output folder (default: out/<session stem>-<method>)")
      ->type_name("DIR");
  run->add_option("--mode", o->mode, "Override the session's mode")
      ->check(CLI::IsMember({"lockstep", "realtime"}));
  run->add_option("--method", o->method, "Override the rendering method (see `mrh methods`)")
      ->type_name("NAME");
  run->add_option("--duration", o->duration, "Override the run length in seconds")
      ->type_name("S")
      ->check(CLI::Validator(CheckPositive, ""));
  AddSetOption(*run, &o->sets);
  run->add_flag("--quiet,-q", o->quiet, "Print only the report: and summary: lines (and warnings)");
  run->add_flag("--progress", o->progress,
                "Show the progress bar even when stderr is not a terminal");
  run->footer(kRunFooter);
  return run;
}

// The report plot, the warnings (once, at the end, even with --quiet: they mean wrong physics or
// timing), the summary and device faults, and where the files went.
void PrintRunResults(const RunOptions& o, const engine::RunStats& stats, const fs::path& out,
                     const device::Device* device) {
  std::string why;
  const bool plotted = report::PlotRunReport(out, o.session, stats, &why);
  if (!plotted) fmt::print(stderr, "mrh: warning: no report.png: {}\n", why);
  for (const std::string& warning : stats.warnings) {
    fmt::print(stderr, "mrh: warning: {}\n", warning);
  }
  if (!o.quiet) PrintSummary(stats);
  if (device != nullptr) PrintDeviceFaults(*device);
  if (plotted) fmt::print("report: {}\n", (out / "report.png").string());
  fmt::print("summary: {}\n", (out / "summary.json").string());
}

namespace {

// The device is built here (not by MakeEngine) to read its fault counters after the run.
// Several pointers: the engine builds and owns every device (their counters reach summary.json
// per pointer), and the engine always owns the loop: null.
std::unique_ptr<device::Device> OwnedDevice(const session::Session& s) {
  return s.pointer_devices.empty() ? session::MakeDevice(s) : nullptr;
}

// The run's engine: with several pointers it builds and owns every device, with one it takes
// `device` (null then).
std::unique_ptr<engine::Engine> MakeRunEngine(const session::Session& s,
                                              std::unique_ptr<device::Device> device) {
  if (!s.pointer_devices.empty()) return session::MakeEngine(s);
  return session::MakeEngine(s, std::move(device));
}

// Closes the CSV files of a run that ended in a fault; a failure there is not reported (the
// fault is the error to report, not a CSV's).
void KeepRecordsUpToFault(report::CsvRecorder* recorder, const fs::path& out) {
  try {
    recorder->Close();
    fmt::print("records up to the fault: {}\n", out.string());
  } catch (const std::exception&) {
  }
}

}  // namespace

int RunCommand(const RunOptions& o) {
  const session::Session s = session::LoadSession(o.session, Overrides(o));
  CheckStudy(o.session, Overrides(o));
  std::unique_ptr<device::Device> owned_device = OwnedDevice(s);
  device::Device* device = owned_device.get();
  // A device whose vendor scheduler owns the servo thread runs the engine inside its callback
  // (real time); otherwise the engine owns the loop.
  auto* servo = dynamic_cast<device::ServoDevice*>(device);
  const bool on_servo_thread = servo != nullptr && s.engine.mode == settings::Mode::kRealtime;
  std::unique_ptr<engine::Engine> engine =
      on_servo_thread ? nullptr : MakeRunEngine(s, std::move(owned_device));
  const fs::path out = OutputDir(o, s);
  report::CsvRecorder recorder(out, engine ? engine->pointer_names() : std::vector<std::string>{});

  ProgressBar bar(
      ProgressSettings{.enabled = !o.quiet && (o.progress || ::isatty(STDERR_FILENO) == 1),
                       .realtime = s.engine.mode == settings::Mode::kRealtime,
                       .duration = s.engine.duration});
  const auto update = [&](double f) {
    bar.Update(f);
  };
  engine::RunStats stats;
  try {
    stats = on_servo_thread ? RunOnServoThread(s, servo, &recorder, update)
                            : engine->Run(&recorder, update);
  } catch (...) {
    // A fault (a diverged simulation) ends the run: keep what was recorded up to it, the
    // evidence of what diverged, then report the fault.
    bar.Finish();
    KeepRecordsUpToFault(&recorder, out);
    throw;
  }
  bar.Finish();
  recorder.Close();
  report::WriteSummary(out, stats, s.file.string(), s.scene.string());

  PrintRunResults(o, stats, out, device);
  return kExitOk;
}

}  // namespace mrh::cli
