# SPDX-License-Identifier: Apache-2.0
# `mrh run` with the real-device types, against the fake vendor libraries built by tests/device.
if(TARGET mrh_fake_hd)
  mrh_cli_test(RunMissingVendorLibraryExits2NamingPathAndReason 2 stderr
               "^mrh: error: .*cannot load the Force Dimension DHD library .*libdhd-missing\\.so.*cannot open shared object"
               run ${fixtures}/tiny.json --quiet --out ${CMAKE_CURRENT_BINARY_DIR}/run_fd_missing
               --set "device={\"type\": \"forcedimension\", \"library\": \"libdhd-missing.so\"}")
  mrh_cli_test(RunForceDimensionThroughTheFakeDhd 0 stdout "^summary: "
               run ${fixtures}/tiny.json --quiet --duration 0.1
               --out ${CMAKE_CURRENT_BINARY_DIR}/run_fd
               --set "device={\"type\": \"forcedimension\", \"model\": \"omega.3\", \"library\": \"$<TARGET_FILE:mrh_fake_dhd>\"}")
  # The fake HD scheduler runs a thread (FAKEHD_THREAD=1): the engine ticks inside its callback.
  mrh_cli_test(RunOpenHapticsOnTheVendorsServoThread 0 stdout "^summary: "
               run ${fixtures}/tiny.json --quiet --mode realtime --duration 0.3
               --set realtime_priority=false --out ${CMAKE_CURRENT_BINARY_DIR}/run_oh
               --set "device={\"type\": \"openhaptics\", \"model\": \"touch\", \"library\": \"$<TARGET_FILE:mrh_fake_hd>\"}")
  set_tests_properties(cli.RunOpenHapticsOnTheVendorsServoThread PROPERTIES
                       ENVIRONMENT FAKEHD_THREAD=1)
endif()


# A `udp` session in real time against a Python test client (docs/devices.md's packets): the
# device's counters (poses received, malformed packets dropped, pose timeouts, wrenches sent)
# must reach summary.json's "device" block and agree with what the client sent.
find_package(Python3 COMPONENTS Interpreter)
if(Python3_Interpreter_FOUND)
  add_test(NAME cli.RunUdpSessionCountsLandInSummary
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_LIST_DIR}/udp_session_test.py ${mrh_bin}
                   ${fixtures}/tiny.json ${CMAKE_CURRENT_BINARY_DIR}/run_udp
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.RunUdpSessionCountsLandInSummary PROPERTIES LABELS apps TIMEOUT 120)
  # Two pointers on two UDP ports in one real-time run: each client moves its own finger and
  # gets that finger's wrenches back; summary.json counts each port's poses.
  add_test(NAME cli.RunTwoUdpPointersEachOnItsOwnPort
           COMMAND ${Python3_EXECUTABLE} ${CMAKE_CURRENT_LIST_DIR}/udp_pointers_session_test.py
                   ${mrh_bin} ${PROJECT_SOURCE_DIR}/scenes/two_finger_grasp.json
                   ${CMAKE_CURRENT_BINARY_DIR}/run_udp_pointers
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.RunTwoUdpPointersEachOnItsOwnPort PROPERTIES LABELS apps TIMEOUT 120)
endif()
