// SPDX-License-Identifier: Apache-2.0
// mrhaptics.run: runs a session as `mrh run` does and returns its records as numpy arrays.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <optional>

#include "bindings.h"
#include "mrh/core/error.h"
#include "mrh/device/hardware.h"
#include "mrh/engine/engine.h"
#include "mrh/report/column_recorder.h"
#include "mrh/report/report.h"

namespace mrh::python {
namespace {

namespace fs = std::filesystem;

/// What run() returns; the arrays are copies the caller owns.
struct Result {
  py::dict ticks, bodies, steps;
  py::object summary;
};

// Hands each record to the column recorder and, when `out` was given, to the CLI's CSV writer.
class TeeRecorder final : public physics::Recorder {
 public:
  TeeRecorder(physics::Recorder* first, physics::Recorder* second) : a_(first), b_(second) {}

  void OnTick(const ir::TickRecord& tick) override {
    a_->OnTick(tick);
    if (b_ != nullptr) b_->OnTick(tick);
  }

  void OnStep(const physics::StepRecord& step, const world::World& world) override {
    a_->OnStep(step, world);
    if (b_ != nullptr) b_->OnStep(step, world);
  }

 private:
  physics::Recorder* a_;
  physics::Recorder* b_;
};

py::dict ToDict(const std::vector<report::Column>& columns) {
  py::dict out;
  for (const report::Column& c : columns) {
    const py::str name(c.name.data(), c.name.size());
    if (c.integer) {
      out[name] =
          py::array_t<std::int64_t>(static_cast<py::ssize_t>(c.integers.size()), c.integers.data());
    } else {
      out[name] = py::array_t<double>(static_cast<py::ssize_t>(c.reals.size()), c.reals.data());
    }
  }
  return out;
}

// bodies.csv's "body" column holds names: the recorder's body ids mapped through its name table
// into a numpy array of str.
py::dict BodiesToDict(const report::ColumnRecorder& recorder) {
  py::dict out = ToDict(recorder.bodies());
  const py::module_ np = py::module_::import("numpy");
  const py::object names = np.attr("array")(recorder.body_names(), py::arg("dtype") = "str");
  out["body"] = names.attr("__getitem__")(out["body"]);
  return out;
}

// The session run() executes: the loaded one, or reloaded with `mode=` appended to its
// overrides exactly as `mrh run --mode` does.
session::Session SessionForMode(const PythonSession& s, const std::string& mode) {
  if (mode != "lockstep" && mode != "realtime") {
    throw InvalidArgument("run: mode = '" + mode + "'; expected \"lockstep\" or \"realtime\"");
  }
  if (mode == settings::ModeName(s.session.engine.mode)) return s.session;
  std::vector<std::string> overrides = s.overrides;
  overrides.push_back("mode=" + mode);
  return session::LoadSession(s.path, overrides);
}

// A vendor servo thread (OpenHaptics) drives real-time runs only through `mrh run`.
void CheckDevice(const session::Session& s, const device::Device& device) {
  if (s.engine.mode == settings::Mode::kRealtime &&
      dynamic_cast<const device::ServoDevice*>(&device) != nullptr) {
    throw InvalidArgument(s.file.string() + ": device.type = \"" + s.device.type +
                          "\" runs real time on the vendor's servo thread, which only `mrh run` "
                          "drives; use mode=\"lockstep\" or the CLI");
  }
}

// Closes a run's output folder `out`: its CSV files, summary.json and report.png (a Python
// warning says why when there is no plot).
void CloseFiles(report::CsvRecorder* csv, const fs::path& out, const engine::RunStats& stats,
                const session::Session& s) {
  const fs::path dir = fs::absolute(out).lexically_normal();
  csv->Close();
  report::WriteSummary(dir, stats, s.file.string(), s.scene.string());
  std::string why;
  if (!report::PlotRunReport(dir, s.file, stats, &why)) {
    PyErr_WarnEx(PyExc_RuntimeWarning, ("no report.png: " + why).c_str(), 1);
  }
}

// Runs with the GIL released. Every progress call (at most every 0.1 s, on this thread) takes
// the GIL back briefly to run Python's signal handlers: a KeyboardInterrupt there asks the
// engine to stop, and is raised once the run has ended and its files are closed.
Result Run(const PythonSession& ps, const std::string& mode, const std::optional<fs::path>& out) {
  const session::Session s = SessionForMode(ps, mode);
  std::unique_ptr<device::Device> device = session::MakeDevice(s);
  CheckDevice(s, *device);
  std::unique_ptr<engine::Engine> engine = session::MakeEngine(s, std::move(device));

  report::ColumnRecorder columns;
  const settings::EngineSettings& settings = engine->settings();
  const auto ticks = std::llround(settings.duration / settings.haptic_dt);
  columns.Reserve(ticks, ticks / settings.ticks_per_step() + 1);
  std::optional<report::CsvRecorder> csv;
  if (out) csv.emplace(fs::absolute(*out).lexically_normal());
  TeeRecorder tee(&columns, csv ? &*csv : nullptr);

  std::optional<py::error_already_set> interrupt;
  const auto progress = [&](double) {
    const py::gil_scoped_acquire gil;
    if (!interrupt && PyErr_CheckSignals() != 0) {
      interrupt.emplace();
      engine->RequestStop();
    }
  };
  engine::RunStats stats;
  {
    const py::gil_scoped_release no_gil;
    stats = engine->Run(&tee, progress);
  }
  const std::string summary = report::SummaryJson(stats, s.file.string(), s.scene.string());
  if (csv) CloseFiles(&*csv, *out, stats, s);
  if (interrupt) throw *interrupt;
  return Result{ToDict(columns.ticks()), BodiesToDict(columns), ToDict(columns.steps()),
                JsonToPython(summary)};
}

}  // namespace

void BindRun(py::module_& m) {
  py::class_<Result>(m, "Result",
                     "What run() returns: the run's records as dicts of numpy arrays keyed by\n"
                     "the CSV columns of `mrh run`, and its summary.")
      .def_readonly("ticks", &Result::ticks,
                    "ticks.csv as columns, one value per haptic tick (world frame): t (s); px, "
                    "py, pz (m);\nqw, qx, qy, qz; fx, fy, fz (N); tx, ty, tz (N m): float64; "
                    "contacts: int64.")
      .def_readonly("bodies", &Result::bodies,
                    "bodies.csv as columns, one value per moving body per physics step (world\n"
                    "frame): t (s); body (str); x, y, z (m, centre of mass); qw, qx, qy, qz; "
                    "vx, vy, vz (m/s);\nwx, wy, wz (rad/s).")
      .def_readonly("steps", &Result::steps,
                    "steps.csv as columns, one value per physics step (timings in ms of wall "
                    "clock).")
      .def_readonly("summary", &Result::summary, "summary.json as a dict.")
      .def("__repr__", [](const Result& r) {
        return "<mrhaptics.Result " + std::to_string(py::len(r.ticks["t"])) + " ticks, " +
               std::to_string(py::len(r.steps["t"])) + " steps>";
      });

  m.def("run", &Run, py::arg("session"), py::arg("mode") = "lockstep", py::arg("out") = py::none(),
        R"(Runs a session as `mrh run` does and returns a Result.

mode: "lockstep" (virtual time, deterministic: the arrays equal `mrh run --mode lockstep`'s
CSV files bit for bit) or "realtime" (a physics and a haptic thread against the wall clock).
It overrides the session's own mode, as `mrh run --mode` does.
out: a folder (str or path); if given, also writes the CLI's files there: ticks.csv,
bodies.csv, steps.csv, summary.json and report.png (a RuntimeWarning if gnuplot is missing).

The GIL is released while the session runs, so other Python threads go on. Ctrl-C
(KeyboardInterrupt, seen within 0.1 s when run is called from the main thread) stops the
run, closes and finishes the files in `out`, then raises.
Raises ValueError for bad input (the CLI's one-line message), RuntimeError when the run
fails (I/O, unrecoverable physics).)");
}

}  // namespace mrh::python
