# SPDX-License-Identifier: Apache-2.0
# Tests of `mrh view` (included by tests/apps/CMakeLists.txt, where mrh_cli_test is defined).
mrh_cli_test(ViewHelpShowsExamples 0 stdout "^Examples:" view --help)
mrh_cli_test(ViewMissingSessionFileExits2NamingThePath 2 stderr
             "^mrh: error: .*no_such_session\\.json" view no_such_session.json)
mrh_cli_test(ViewScreenshotNeedsFrames 2 stderr "^mrh: error: .*--screenshot requires --frames"
             view ${fixtures}/tiny.json --screenshot never.png)
mrh_cli_test(ViewBadSessionKeyExits2NamingTheKey 2 stderr "^mrh: error: .*bogus_key"
             view ${fixtures}/unknown_key.json)
mrh_cli_test(ViewAtExcludesFrames 2 stderr "^mrh: error: --(at excludes --frames|frames excludes --at)$"
             view ${fixtures}/tiny.json --at 1 --frames 3)
mrh_cli_test(ViewAtMustNotBeNegative 2 stderr
             "^mrh: error: --at: expected a simulated time in seconds >= 0, got '-0\\.5'$"
             view ${fixtures}/tiny.json --at -0.5)
mrh_cli_test(ViewHelpSaysFramesLandAtNoFixedTime 0 stdout "use --at to aim at a simulated time"
             view --help)

if(TARGET mrh_viewer)
  # No display: one line saying so, suggesting xvfb-run and `mrh run`; a runtime error (exit 1),
  # since the input is fine and the environment is not.
  add_test(NAME cli.ViewWithoutDisplayExits1SuggestingXvfb
           COMMAND ${expect} 1 stderr
                   "^mrh: error: no display available for 'mrh view' \\(DISPLAY is not set\\); run it under xvfb-run \\(xvfb-run -a mrh view \\.\\.\\.\\) or use 'mrh run' for a headless session$"
                   -- env -u DISPLAY ${mrh_bin} view ${fixtures}/tiny.json
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.ViewWithoutDisplayExits1SuggestingXvfb PROPERTIES LABELS apps
                       TIMEOUT 60)

  # Headless screenshots under Xvfb (label `viewer`; skipped without xvfb-run).
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(stb REQUIRED IMPORTED_TARGET stb)
  add_executable(view_screenshot_check ${CMAKE_CURRENT_LIST_DIR}/view_screenshot_check.cc)
  target_link_libraries(view_screenshot_check PRIVATE PkgConfig::stb)
  mrh_set_warnings(view_screenshot_check)
  set(view_test ${CMAKE_CURRENT_LIST_DIR}/view_screenshot_test.sh)
  set(check $<TARGET_FILE:view_screenshot_check>)
  add_test(NAME viewer.ScreenshotShowsFloorAndCubes
           COMMAND ${view_test} ${mrh_bin} ${check} scenes/demo.json
                   ${CMAKE_CURRENT_BINARY_DIR}/view_scene.png 30
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  add_test(NAME viewer.ScreenshotShowsThePanel
           COMMAND ${view_test} ${mrh_bin} ${check} scenes/demo.json
                   ${CMAKE_CURRENT_BINARY_DIR}/view_panel.png 30 --panel
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  # The pointer held 1 cm into the floor: a steady 10 N up from the first frames, so the arrow
  # shows whatever the frame rate (in demo.json contact starts ~2 s in, after a frame-rate
  # dependent number of frames).
  add_test(NAME viewer.ScreenshotShowsTheForceArrow
           COMMAND ${view_test} ${mrh_bin} ${check} ${fixtures}/view_press.json
                   ${CMAKE_CURRENT_BINARY_DIR}/view_force.png 30 --force
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  # --at: the session held at exactly 0.75 s (past the 0.5 s engage ramp; the printed time is
  # the newest tick's, drawn in the shot), whatever the frame rate; the shot shows the floor and
  # the force arrow.
  add_test(NAME viewer.AtHoldsTheSessionAtTheRequestedTime
           COMMAND ${expect} 0 stdout "^screenshot: .*view_at\\.png \\(t = 0\\.750 s\\)$"
                   -- ${view_test} ${mrh_bin} ${check} ${fixtures}/view_press.json
                   ${CMAKE_CURRENT_BINARY_DIR}/view_at.png --at=0.75 --force
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  # Under ASan, LeakSanitizer would report what the X, GLX and Mesa libraries keep until exit
  # (not ours): leaks are checked by the GL-free viewer_test instead.
  set_tests_properties(viewer.ScreenshotShowsFloorAndCubes viewer.ScreenshotShowsThePanel
                       viewer.ScreenshotShowsTheForceArrow viewer.AtHoldsTheSessionAtTheRequestedTime
                       PROPERTIES LABELS viewer TIMEOUT 120 SKIP_RETURN_CODE 77
                                  ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0")
else()
  mrh_cli_test(ViewWithoutViewerBuildSaysHowToGetIt 1 stderr
               "^mrh: error: this mrh was built without the viewer .*install-deps\\.sh"
               view ${fixtures}/tiny.json)
endif()

# Unit tests of the viewer's GL-free parts (tests/viewer/): feed, haptic loop, session restarts,
# pointer control, recording, plots, the proxy ghost. No display needed. Label `threaded`: they
# start the haptic and physics threads, so the TSan preset runs them with the `engine` tests.
if(TARGET mrh_viewer)
  file(GLOB viewer_test_sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/tests/viewer/*_test.cc)
  mrh_test(viewer_test LABEL threaded SOURCES ${viewer_test_sources} DEPS mrh_viewer)
endif()
