// SPDX-License-Identifier: Apache-2.0
// The extension module mrhaptics._mrhaptics: error mapping, methods() and the bound classes.
#include <pybind11/stl.h>

#include <exception>

#include "bindings.h"
#include "mrh/core/error.h"
#include "mrh/engine/method.h"

namespace mrh::python {

py::object JsonToPython(const std::string& text) {
  return py::module_::import("json").attr("loads")(text);
}

namespace {

// Bad user input (session keys, scenes, poses) is a ValueError carrying the one-line message
// the CLI prints after "mrh: error: "; mrh::RuntimeError (I/O, physics failure) stays a
// RuntimeError through pybind11's std::runtime_error mapping.
void TranslateErrors(std::exception_ptr error) {
  try {
    if (error) std::rethrow_exception(error);
  } catch (const InvalidArgument& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  } catch (const SceneError& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  }
}

std::vector<std::string> MethodNames() {
  std::vector<std::string> names;
  for (const auto& [name, summary] : engine::ListMethods()) names.push_back(name);
  return names;
}

}  // namespace

}  // namespace mrh::python

PYBIND11_MODULE(_mrhaptics, m) {
  namespace py = pybind11;
  using namespace mrh::python;
  m.doc() = "mrhaptics' C++ core; import the package `mrhaptics`, which re-exports it.";
  m.attr("__version__") = MRH_VERSION;
  py::register_exception_translator(&TranslateErrors);
  m.def("methods", &MethodNames,
        "The registered rendering methods' names, sorted (what a session's `method` accepts,\n"
        "as `mrh methods` lists them).");
  BindSession(m);
  BindRun(m);
  BindEngine(m);
}
