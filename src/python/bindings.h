// SPDX-License-Identifier: Apache-2.0
// The pieces of the Python module `mrhaptics._mrhaptics`, one Bind function per concept.
#pragma once

#include <pybind11/pybind11.h>

#include <filesystem>
#include <string>
#include <vector>

#include "mrh/session/session.h"

namespace mrh::python {

namespace py = pybind11;

/// A loaded session as Python sees it: the file, the `--set` strings applied to it and the
/// validated result. Immutable once built; run() and Engine copy what they need.
struct PythonSession {
  std::filesystem::path path;
  std::vector<std::string> overrides;  ///< "dotted.key=JSON value", as `mrh run --set`
  session::Session session;
};

/// `json.loads(text)`: summary.json's text as a Python dict. Needs the GIL.
py::object JsonToPython(const std::string& text);

/// Session and _load_session (the overrides' JSON text is made by the Python layer).
void BindSession(py::module_& m);
/// Result and run().
void BindRun(py::module_& m);
/// Engine: the embedded loop with an external device.
void BindEngine(py::module_& m);

}  // namespace mrh::python
