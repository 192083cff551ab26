# SPDX-License-Identifier: Apache-2.0
# cmake -DROOT=<source dir> -P cmake/CheckModuleIncludes.cmake
# The thread boundary in the sources (docs/architecture.md): fails when
#  - a file of a module both threads may run (haptic, render, ir: src/<m>, include/mrh/<m>)
#    includes MuJoCo or an mrh header outside the modules it may use (below);
#  - a file of src/ or apps/ outside src/engine, src/physics and src/haptic includes one of those
#    modules' private headers ("engine/...", "physics/...", "haptic/..."): everything else uses
#    the public headers under include/mrh (tests and benchmarks of internals may include them).
set(allowed_haptic core ir render device haptic)
set(allowed_render core ir render)
set(allowed_ir core ir)
set(errors "")
foreach(module haptic render ir)
  list(JOIN allowed_${module} "|" allowed)
  file(GLOB_RECURSE files ${ROOT}/src/${module}/*.h ${ROOT}/src/${module}/*.cc
       ${ROOT}/include/mrh/${module}/*.h)
  foreach(f ${files})
    file(STRINGS ${f} lines REGEX "^#include \"")
    foreach(line ${lines})
      string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" header "${line}")
      if(NOT header MATCHES "^mrh/(${allowed})/" AND header MATCHES "/"
         AND NOT header MATCHES "^${module}/")
        list(APPEND errors "${f}: includes ${header} (the ${module} module may use only ${allowed_${module}})")
      endif()
    endforeach()
    file(STRINGS ${f} angle REGEX "^#include <mujoco")
    if(angle)
      list(APPEND errors "${f}: includes MuJoCo")
    endif()
  endforeach()
endforeach()
file(GLOB_RECURSE other_files ${ROOT}/src/*.h ${ROOT}/src/*.cc ${ROOT}/apps/*.h ${ROOT}/apps/*.cc)
foreach(f ${other_files})
  if(f MATCHES "/src/(engine|physics|haptic)/")
    continue()
  endif()
  file(STRINGS ${f} lines REGEX "^#include \"(engine|physics|haptic)/")
  foreach(line ${lines})
    list(APPEND errors "${f}: ${line} (a private header; use the public one under include/mrh)")
  endforeach()
endforeach()
if(errors)
  list(JOIN errors "\n" text)
  message(FATAL_ERROR "module boundary violated:\n${text}")
endif()
message(STATUS "module boundaries hold (${ROOT})")
