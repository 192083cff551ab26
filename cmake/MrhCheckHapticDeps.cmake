# SPDX-License-Identifier: Apache-2.0
# Build-enforced thread boundary: the haptic module, which holds the 1 kHz tick, must never
# reach MuJoCo or the world, not even transitively, so the real-time code sees only the ir::
# snapshots and cannot call into the simulator. Checked at configure time over
# the link graph; tests/CMakeLists.txt adds a test that scans the haptic sources' includes.

# Collects into `out` every target and library reachable from `target` through link lines.
function(mrh_link_closure target out)
  set(seen "")
  set(todo ${target})
  while(todo)
    list(POP_FRONT todo item)
    if(item IN_LIST seen)
      continue()
    endif()
    list(APPEND seen ${item})
    if(TARGET ${item})
      get_target_property(aliased ${item} ALIASED_TARGET)
      if(aliased)
        list(APPEND todo ${aliased})
      endif()
      foreach(property LINK_LIBRARIES INTERFACE_LINK_LIBRARIES)
        get_target_property(deps ${item} ${property})
        if(deps)
          foreach(dep ${deps})
            # $<LINK_ONLY:x> and other generator expressions around a name.
            string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" dep "${dep}")
            list(APPEND todo ${dep})
          endforeach()
        endif()
      endforeach()
    endif()
  endwhile()
  set(${out} ${seen} PARENT_SCOPE)
endfunction()

# Fails the configure step if `target` reaches any of the FORBIDDEN names.
function(mrh_forbid_links target)
  cmake_parse_arguments(ARG "" "" "FORBIDDEN" ${ARGN})
  mrh_link_closure(${target} closure)
  foreach(bad ${ARG_FORBIDDEN})
    if(bad IN_LIST closure)
      message(FATAL_ERROR "${target} links ${bad} (closure: ${closure}), which crosses a module "
                          "boundary (docs/architecture.md, \"Modules\")")
    endif()
  endforeach()
endfunction()
