# SPDX-License-Identifier: Apache-2.0
# cmake -DROOT=<source dir> -P cmake/CheckModuleIncludes.cmake
# The thread boundary in the sources (docs/architecture.md): fails when
#  - a file of the haptic module (src/haptic, include/mrh/haptic) includes anything but the
#    standard library, Eigen and mrh/{core,ir,render,device,haptic} headers or its own folder.
file(GLOB_RECURSE haptic_files ${ROOT}/src/haptic/*.h ${ROOT}/src/haptic/*.cc
     ${ROOT}/include/mrh/haptic/*.h)
set(errors "")
foreach(f ${haptic_files})
  file(STRINGS ${f} lines REGEX "^#include \"")
  foreach(line ${lines})
    string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" header "${line}")
    if(NOT header MATCHES "^mrh/(core|ir|render|device|haptic)/" AND header MATCHES "/")
      list(APPEND errors "${f}: includes ${header} (the haptic module may use only core, ir, render, device)")
    endif()
  endforeach()
  file(STRINGS ${f} angle REGEX "^#include <mujoco")
  if(angle)
    list(APPEND errors "${f}: includes MuJoCo")
  endif()
endforeach()
if(errors)
  list(JOIN errors "\n" text)
  message(FATAL_ERROR "module boundary violated:\n${text}")
endif()
message(STATUS "module boundaries hold (${ROOT})")
