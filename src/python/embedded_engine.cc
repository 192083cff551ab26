// SPDX-License-Identifier: Apache-2.0
// mrhaptics.Engine: the engine embedded in a Python servo loop (an `external` device).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <optional>
#include <sstream>

#include "bindings.h"
#include "mrh/core/error.h"
#include "mrh/engine/engine.h"
#include "mrh/report/report.h"

namespace mrh::python {
namespace {

// A pose's quaternion may be off unit length by float32 round-off or a device's own
// normalization, never by more: anything farther is a wrong input, not noise to normalize away.
constexpr double kUnitQuaternionTolerance = 1e-3;

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::string Shape(const py::array& a) {
  std::ostringstream out;
  out << '(';
  for (py::ssize_t i = 0; i < a.ndim(); ++i) out << (i > 0 ? ", " : "") << a.shape(i);
  out << (a.ndim() == 1 ? ",)" : ")");
  return out.str();
}

// `value` as `n` finite float64s, else a ValueError that says what `name` must be.
Array FiniteVector(const py::handle& value, py::ssize_t n, const char* name, const char* what) {
  Array a = Array::ensure(value);
  if (!a) {
    throw InvalidArgument(std::string("Engine.tick: ") + name + " is not numeric; expected " +
                          what);
  }
  if (a.ndim() != 1 || a.shape(0) != n) {
    throw InvalidArgument(std::string("Engine.tick: ") + name + " has shape " + Shape(a) +
                          "; expected " + what);
  }
  for (py::ssize_t i = 0; i < n; ++i) {
    if (!std::isfinite(a.at(i))) {
      throw InvalidArgument(std::string("Engine.tick: ") + name + "[" + std::to_string(i) +
                            "] = " + std::to_string(a.at(i)) + "; expected " + what);
    }
  }
  return a;
}

constexpr const char* kPoseExpected =
    "7 finite numbers x, y, z (m), qw, qx, qy, qz (unit quaternion), device frame";
constexpr const char* kVelocityExpected =
    "6 finite numbers vx, vy, vz (m/s), wx, wy, wz (rad/s), device frame";

device::DeviceState Reading(double t, const py::handle& pose, const py::handle& velocity) {
  const Array x = FiniteVector(pose, 7, "pose", kPoseExpected);
  device::DeviceState s;
  s.t = t;
  s.X_DT.p = Vec3(x.at(0), x.at(1), x.at(2));
  s.X_DT.q = Quat(x.at(3), x.at(4), x.at(5), x.at(6));
  const double norm = s.X_DT.q.norm();
  if (std::abs(norm - 1.0) > kUnitQuaternionTolerance) {
    throw InvalidArgument("Engine.tick: pose quaternion (qw, qx, qy, qz) has norm " +
                          std::to_string(norm) + "; expected 1: normalize it");
  }
  s.X_DT.q.normalize();
  if (!velocity.is_none()) {
    const Array v = FiniteVector(velocity, 6, "velocity", kVelocityExpected);
    s.V_DT.v = Vec3(v.at(0), v.at(1), v.at(2));
    s.V_DT.w = Vec3(v.at(3), v.at(4), v.at(5));
  }
  return s;
}

class PythonEngine {
 public:
  explicit PythonEngine(const PythonSession& s) : session_(s.session) {
    if (session_.device.type != "external") {
      throw InvalidArgument(session_.file.string() + ": device.type = \"" + session_.device.type +
                            "\"; Engine needs \"external\" (your loop feeds the poses): load it "
                            "with overrides={\"device\": {\"type\": \"external\"}}, or use run()");
    }
    engine_ = session::MakeEngine(session_);
  }

  PythonEngine(const PythonEngine&) = delete;
  PythonEngine& operator=(const PythonEngine&) = delete;

  // An embedded run must end in Stop(): it joins the real-time physics thread.
  ~PythonEngine() {
    if (state_ == State::kRunning) (void)engine_->Stop();
  }

  void Start() {
    if (state_ != State::kReady) {
      throw std::runtime_error("Engine.start: already started; build a new Engine per run");
    }
    engine_->Start();
    state_ = State::kRunning;
  }

  py::array_t<double> Tick(const py::handle& pose, std::optional<double> t,
                           const py::handle& velocity) {
    if (state_ != State::kRunning) {
      throw std::runtime_error(state_ == State::kReady ? "Engine.tick: call start() first"
                                                       : "Engine.tick: the engine was stopped");
    }
    const double time = t.value_or(last_t_ ? *last_t_ + engine_->settings().haptic_dt : 0.0);
    if (!std::isfinite(time) || time < 0.0 || (last_t_ && time <= *last_t_)) {
      throw InvalidArgument("Engine.tick: t = " + std::to_string(time) +
                            " s; expected a finite time >= 0 after the previous tick's " +
                            std::to_string(last_t_.value_or(0.0)) + " s");
    }
    const device::DeviceState reading = Reading(time, pose, velocity);
    if (busy_.exchange(true)) {
      throw std::runtime_error(
          "Engine.tick: called from two threads at once; one thread drives it");
    }
    Wrench w;
    {
      const py::gil_scoped_release no_gil;
      w = engine_->Tick(time, reading);
    }
    busy_.store(false);
    last_t_ = time;
    py::array_t<double> out(6);
    auto o = out.mutable_unchecked<1>();
    for (int i = 0; i < 3; ++i) {
      o(i) = w.f[i];
      o(i + 3) = w.tau[i];
    }
    return out;
  }

  py::object Stop() {
    if (state_ != State::kRunning) throw std::runtime_error("Engine.stop: not running");
    const engine::RunStats stats = engine_->Stop();
    state_ = State::kStopped;
    stats_ =
        JsonToPython(report::SummaryJson(stats, session_.file.string(), session_.scene.string()));
    return stats_;
  }

  py::object stats() const { return stats_; }

  bool running() const { return state_ == State::kRunning; }

  double haptic_dt() const { return engine_->settings().haptic_dt; }

  std::optional<double> last_t() const { return last_t_; }

 private:
  enum class State { kReady, kRunning, kStopped };
  session::Session session_;
  std::unique_ptr<engine::Engine> engine_;
  State state_ = State::kReady;
  std::optional<double> last_t_;
  std::atomic<bool> busy_{false};
  py::object stats_ = py::none();
};

using EngineClass = py::class_<PythonEngine>;

constexpr const char* kEngineDoc = R"(The engine inside your own servo loop.

For a session whose device.type is "external": your loop reads the device and calls tick()
with its pose; the engine renders and returns the wrench to display. In lockstep mode each
physics step runs inside the tick that begins its period (deterministic); in realtime mode a
physics thread runs beside your loop. Drive one Engine from one thread.

    with mrhaptics.Engine(session) as engine:
        for i in range(1000):
            wrench = engine.tick([0, 0, 0.019, 1, 0, 0, 0])
    stats = engine.stats

Raises ValueError if the session's device is not external.)";

constexpr const char* kTickDoc = R"(One haptic tick; returns the wrench to display.

pose: x, y, z (m), qw, qx, qy, qz, the tool pose in the device frame (any sequence or array
of 7 numbers; the quaternion must be unit to 1e-3 and is normalized).
t: the tick's time (s since start()); defaults to the previous tick's t + haptic_dt (0 first).
Must increase from tick to tick.
velocity: vx, vy, vz (m/s), wx, wy, wz (rad/s), device frame, for the methods' dampers; zero
when omitted.
Returns numpy float64 (6,): fx, fy, fz (N), tx, ty, tz (N m), device frame, after the safety
layer (ramp, limits). Raises ValueError for a non-finite or wrongly shaped pose, velocity or t
(nothing reaches the device then), RuntimeError before start() or after stop(). The GIL is
released while the engine ticks.)";

// The run's state, read-only.
void DefProperties(EngineClass& c) {
  c.def_property_readonly("running", &PythonEngine::running, "Between start() and stop().")
      .def_property_readonly("stats", &PythonEngine::stats,
                             "What stop() returned (also after a `with` block), or None.")
      .def_property_readonly("haptic_dt", &PythonEngine::haptic_dt, "Haptic period (s).")
      .def_property_readonly("last_t", &PythonEngine::last_t,
                             "The last tick's t (s), or None before the first tick.");
}

}  // namespace

void BindEngine(py::module_& m) {
  EngineClass c(m, "Engine", kEngineDoc);
  c.def(py::init<const PythonSession&>(), py::arg("session"))
      .def("start", &PythonEngine::Start,
           "Starts the run (t = 0). Raises RuntimeError if started "
           "before.")
      .def("tick", &PythonEngine::Tick, py::arg("pose"), py::arg("t") = py::none(),
           py::arg("velocity") = py::none(), kTickDoc)
      .def("stop", &PythonEngine::Stop,
           "Ends the run (zero output, physics thread joined) and returns its statistics as "
           "summary.json's dict.");
  DefProperties(c);
  c.def(
       "__enter__",
       [](PythonEngine& e) -> PythonEngine& {
         e.Start();
         return e;
       },
       py::return_value_policy::reference_internal)
      .def("__exit__", [](PythonEngine& e, const py::args&) {
        if (e.running()) (void)e.Stop();
        return false;
      });
}

}  // namespace mrh::python
