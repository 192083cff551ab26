# SPDX-License-Identifier: Apache-2.0
# Methods from the command line on the shared scenes, with nothing but --method: a user who picks a
# baseline must not have to tune it first. The light tools of demo.json (hand device) and
# t3_6_push.json (box pointer pushing a box on a floor) need virtual-coupling's rotational gains
# from the tool's inertia (rendering.coupling_rot_* unset); fixed gains made both exit 2. A run
# that exits 0 but warns (MuJoCo's "bad number in qacc" resets, non-finite wrenches) fails too;
# only the missing-gnuplot notice ("warning: no report.png") is allowed.
foreach(session demo t3_6_push)
  add_test(NAME cli.VirtualCouplingRunsWithoutWarnings_${session}
           COMMAND ${mrh_bin} run scenes/${session}.json --method virtual-coupling --duration 1.5
                   --out ${CMAKE_CURRENT_BINARY_DIR}/vc_${session} --quiet
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.VirtualCouplingRunsWithoutWarnings_${session} PROPERTIES
                       LABELS apps TIMEOUT 120
                       FAIL_REGULAR_EXPRESSION "mrh: error;mrh: warning: [^n];mrh: warning: n[^o]")
endforeach()
