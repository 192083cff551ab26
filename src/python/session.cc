// SPDX-License-Identifier: Apache-2.0
// mrhaptics.Session: a session file loaded, overridden and validated as `mrh run` does it.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "mrh/settings/settings.h"

namespace mrh::python {
namespace {

PythonSession LoadSession(const std::filesystem::path& path, std::vector<std::string> overrides) {
  PythonSession s;
  s.path = path;
  s.overrides = std::move(overrides);
  s.session = session::LoadSession(s.path, s.overrides);
  return s;
}

std::string Repr(const PythonSession& s) {
  return "<mrhaptics.Session " + s.path.string() + ": method " + s.session.engine.method + ", " +
         settings::ModeName(s.session.engine.mode) + ", device " + s.session.device.type + ">";
}

using SessionClass = py::class_<PythonSession>;

// Where the session came from: its file, overrides and scene.
void DefSourceProperties(SessionClass& c) {
  c.def_property_readonly(
       "path",
       [](const PythonSession& s) {
         return s.path;
       },
       "The session file, as given.")
      .def_property_readonly(
          "overrides",
          [](const PythonSession& s) {
            return s.overrides;
          },
          "The overrides applied, as `mrh run --set` strings (\"key=JSON value\").")
      .def_property_readonly(
          "scene",
          [](const PythonSession& s) {
            return s.session.scene;
          },
          "The scene (MJCF) file, resolved against the session's folder.");
}

// How it runs: method, mode, duration and rates.
void DefRunProperties(SessionClass& c) {
  c.def_property_readonly(
       "method",
       [](const PythonSession& s) {
         return s.session.engine.method;
       },
       "The rendering method (one of methods()).")
      .def_property_readonly(
          "mode",
          [](const PythonSession& s) {
            return settings::ModeName(s.session.engine.mode);
          },
          "\"lockstep\" or \"realtime\", as the file says (run() picks its own).")
      .def_property_readonly(
          "duration",
          [](const PythonSession& s) {
            return s.session.engine.duration;
          },
          "Run length (s): simulated time in lockstep, wall time in real time.")
      .def_property_readonly(
          "haptic_dt",
          [](const PythonSession& s) {
            return s.session.engine.haptic_dt;
          },
          "Haptic period (s).")
      .def_property_readonly(
          "physics_dt",
          [](const PythonSession& s) {
            return s.session.engine.physics_dt;
          },
          "Physics step as configured (s); single-rate methods step at haptic_dt instead.");
}

}  // namespace

void BindSession(py::module_& m) {
  SessionClass c(m, "Session",
                 "A validated session (scene, method, rates, gains, device).\n\n"
                 "Made by load_session(); read-only. run() and Engine use it.");
  DefSourceProperties(c);
  DefRunProperties(c);
  c.def_property_readonly(
       "device_type",
       [](const PythonSession& s) {
         return s.session.device.type;
       },
       "device.type: fixed, scripted, hand, replay, external, ...")
      .def("__repr__", &Repr);

  m.def("_load_session", &LoadSession, py::arg("path"), py::arg("overrides"),
        "load_session() after the overrides became \"key=JSON\" strings. Raises ValueError.");
}

}  // namespace mrh::python
