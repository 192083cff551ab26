# SPDX-License-Identifier: Apache-2.0
# mrh_module(NAME SOURCES ... DEPS ...): one static library per module; its link line fixes the
# dependency direction between modules, so a dependency cycle fails the build.
function(mrh_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -ffp-contract=off)
  if(MRH_WERROR)
    # GCC 12 at -O2 reports false -Wrestrict/-Wstringop-overflow errors inside libstdc++'s
    # std::string (GCC bug 105329): keep them as warnings, everything else an error.
    target_compile_options(${target} PRIVATE -Werror -Wno-error=restrict
                                             -Wno-error=stringop-overflow)
  endif()
endfunction()

# APART: a module the CLI links but library users do not (experiments, psychophysics): it is
# left out of mrhaptics::mrhaptics and of the installed package, as samples are kept apart from
# a physics library.
function(mrh_module name)
  cmake_parse_arguments(ARG "APART" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(mrh_${name} STATIC ${ARG_SOURCES})
  add_library(mrhaptics::${name} ALIAS mrh_${name})
  target_include_directories(mrh_${name} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:include>
    PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(mrh_${name} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  mrh_set_warnings(mrh_${name})
  if(ARG_APART)
    set_property(GLOBAL APPEND PROPERTY MRH_APART_MODULES mrh_${name})
  else()
    set_property(GLOBAL APPEND PROPERTY MRH_MODULES mrh_${name})
  endif()
endfunction()

# mrh_test(NAME LABEL SOURCES ... DEPS ...): one GoogleTest executable per module.
# A `slow` test is neither built nor registered when MRH_SLOW_TESTS is OFF (sanitizer presets).
# GROUPED_SUITES: GoogleTest suites registered as one ctest test each (`<Suite>`, running
# --gtest_filter=<Suite>.*) instead of one per test: suites whose SetUpTestSuite runs a whole
# experiment, which one process per test would repeat for every test of the suite.
function(mrh_test name)
  cmake_parse_arguments(ARG "" "LABEL" "SOURCES;DEPS;GROUPED_SUITES" ${ARGN})
  if(ARG_LABEL STREQUAL "slow" AND NOT MRH_SLOW_TESTS)
    return()
  endif()
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gmock GTest::gtest_main)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR}/src ${PROJECT_SOURCE_DIR}/tests)
  target_compile_definitions(${name} PRIVATE MRH_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  mrh_set_warnings(${name})
  if(NOT ARG_LABEL)
    set(ARG_LABEL unit)
  endif()
  set(filter "*")
  if(ARG_GROUPED_SUITES)
    list(TRANSFORM ARG_GROUPED_SUITES APPEND ".*" OUTPUT_VARIABLE patterns)
    list(JOIN patterns ":" joined)
    set(filter "-${joined}")
    foreach(suite IN LISTS ARG_GROUPED_SUITES)
      add_test(NAME ${suite} COMMAND ${name} --gtest_filter=${suite}.*
               WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
      set_tests_properties(${suite} PROPERTIES LABELS "${ARG_LABEL}")
    endforeach()
  endif()
  gtest_discover_tests(${name} TEST_FILTER "${filter}" PROPERTIES LABELS "${ARG_LABEL}"
                       DISCOVERY_TIMEOUT 60 WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
endfunction()
