# SPDX-License-Identifier: Apache-2.0
# mujoco::mujoco from the pinned PyPI `mujoco` wheel that scripts/install-deps.sh unpacks into
# MRH_MUJOCO_ROOT (default <source>/build/deps/mujoco): its C headers and libmujoco.so.<version>.
# The version is pinned in scripts/mujoco-version.txt; a missing or different MuJoCo is a fatal
# error that names the command to run. Executables linked here get the library's directory in
# their build RPATH (CMake's default), so build/bin/mrh runs from anywhere; installed binaries
# find the copy installed beside the module libraries ($ORIGIN/../lib).
file(STRINGS ${PROJECT_SOURCE_DIR}/scripts/mujoco-version.txt MRH_MUJOCO_VERSION LIMIT_COUNT 1)
set(MRH_MUJOCO_ROOT "${PROJECT_SOURCE_DIR}/build/deps/mujoco" CACHE PATH
    "Folder of the unpacked mujoco wheel (holds include/mujoco and libmujoco.so.<version>)")

set(_mrh_mj_hint "run scripts/install-deps.sh (or make deps) to install MuJoCo ${MRH_MUJOCO_VERSION}")
set(_mrh_mj_header "${MRH_MUJOCO_ROOT}/include/mujoco/mujoco.h")
set(_mrh_mj_lib "${MRH_MUJOCO_ROOT}/libmujoco.so.${MRH_MUJOCO_VERSION}")
if(NOT EXISTS "${_mrh_mj_header}")
  message(FATAL_ERROR "MuJoCo not found: no ${_mrh_mj_header}; ${_mrh_mj_hint}")
endif()
file(STRINGS "${_mrh_mj_header}" _mrh_mj_line REGEX "^#define mjVERSION_HEADER [0-9]+")
string(REGEX REPLACE "^#define mjVERSION_HEADER ([0-9]+).*" "\\1" _mrh_mj_code "${_mrh_mj_line}")
string(REPLACE "." ";" _mrh_mj_parts "${MRH_MUJOCO_VERSION}")
list(GET _mrh_mj_parts 0 _mj_major)
list(GET _mrh_mj_parts 1 _mj_minor)
list(GET _mrh_mj_parts 2 _mj_patch)
math(EXPR _mrh_mj_want "${_mj_major} * 1000000 + ${_mj_minor} * 1000 + ${_mj_patch}")
if(NOT _mrh_mj_code STREQUAL _mrh_mj_want)
  message(FATAL_ERROR "MuJoCo in ${MRH_MUJOCO_ROOT} is version code ${_mrh_mj_code}, expected "
                      "${MRH_MUJOCO_VERSION} (${_mrh_mj_want}); ${_mrh_mj_hint}")
endif()
if(NOT EXISTS "${_mrh_mj_lib}")
  message(FATAL_ERROR "MuJoCo library not found: no ${_mrh_mj_lib}; ${_mrh_mj_hint}")
endif()

add_library(mujoco::mujoco SHARED IMPORTED GLOBAL)
set_target_properties(mujoco::mujoco PROPERTIES
  IMPORTED_LOCATION "${_mrh_mj_lib}"
  IMPORTED_SONAME "libmujoco.so.${MRH_MUJOCO_VERSION}"
  INTERFACE_INCLUDE_DIRECTORIES "${MRH_MUJOCO_ROOT}/include")
set(MRH_MUJOCO_LIBRARY "${_mrh_mj_lib}")
message(STATUS "MuJoCo ${MRH_MUJOCO_VERSION}: ${_mrh_mj_lib}")
