# SPDX-License-Identifier: Apache-2.0
# The Python module `mrhaptics` (src/python) for the python3 on PATH, with pybind11 and numpy
# from the pinned packages scripts/install-deps.sh puts into MRH_PYTHON_DEPS_DIR (default
# <source>/build/deps/python; scripts/python-requirements.txt). The build writes the package to
# <build>/python/mrhaptics; `make install` (cmake --install --component python) copies it into
# MRH_PYTHON_INSTALL_DIR, the interpreter's site-packages unless set. Sanitizer presets turn it
# off: an ASan/TSan-instrumented module cannot load into an uninstrumented interpreter.
option(MRH_BUILD_PYTHON "Build the Python module mrhaptics (build/python)" ON)
if(NOT MRH_BUILD_PYTHON)
  return()
endif()

set(MRH_PYTHON_DEPS_DIR "${PROJECT_SOURCE_DIR}/build/deps/python" CACHE PATH
    "Folder of the pinned Python packages (pybind11, numpy, pytest) that install-deps unpacks")
set(_mrh_py_hint "run scripts/install-deps.sh (or make deps), or configure with -DMRH_BUILD_PYTHON=OFF")

# The python3 on PATH, resolved past launchers such as pyenv's shims to the interpreter itself.
find_program(MRH_PYTHON3_ON_PATH python3 NO_CACHE)
if(NOT MRH_PYTHON3_ON_PATH)
  message(FATAL_ERROR "Python module: no python3 on PATH; ${_mrh_py_hint}")
endif()
execute_process(COMMAND ${MRH_PYTHON3_ON_PATH} -c "import sys; print(sys.executable)"
                OUTPUT_VARIABLE _mrh_py_exe OUTPUT_STRIP_TRAILING_WHITESPACE
                RESULT_VARIABLE _mrh_py_rc)
if(NOT _mrh_py_rc EQUAL 0 OR NOT EXISTS "${_mrh_py_exe}")
  message(FATAL_ERROR "Python module: ${MRH_PYTHON3_ON_PATH} does not run; ${_mrh_py_hint}")
endif()
set(Python_EXECUTABLE "${_mrh_py_exe}" CACHE FILEPATH "The interpreter the module is built for")
find_package(Python 3.8 REQUIRED COMPONENTS Interpreter Development.Module)

set(pybind11_DIR "${MRH_PYTHON_DEPS_DIR}/pybind11/share/cmake/pybind11" CACHE PATH
    "pybind11's CMake package (from the pinned wheel)" FORCE)
if(NOT EXISTS "${pybind11_DIR}/pybind11Config.cmake")
  message(FATAL_ERROR "Python module: pybind11 not found in ${MRH_PYTHON_DEPS_DIR}; ${_mrh_py_hint}")
endif()
set(PYBIND11_FINDPYTHON ON)
find_package(pybind11 3.1 CONFIG REQUIRED)

execute_process(COMMAND ${Python_EXECUTABLE} -c
                        "import sysconfig; print(sysconfig.get_paths()['platlib'])"
                OUTPUT_VARIABLE _mrh_py_site OUTPUT_STRIP_TRAILING_WHITESPACE)
set(MRH_PYTHON_INSTALL_DIR "${_mrh_py_site}" CACHE PATH
    "Where `make install` puts the mrhaptics package (default: python3's site-packages)")
message(STATUS "Python module for ${Python_EXECUTABLE} (${Python_VERSION}), pybind11 "
               "${pybind11_VERSION}; installs into ${MRH_PYTHON_INSTALL_DIR}")
