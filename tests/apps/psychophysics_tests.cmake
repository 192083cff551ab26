# SPDX-License-Identifier: Apache-2.0
# Tests of `mrh psychophysics` (included by tests/apps/CMakeLists.txt, where mrh_cli_test is
# defined).
mrh_cli_test(PsychophysicsHelpShowsExamples 0 stdout "^Examples:" psychophysics --help)
mrh_cli_test(PsychophysicsWithoutSubcommandExits2 2 stderr "A subcommand is required" psychophysics)
mrh_cli_test(PsychophysicsRunNeedsASubject 2 stderr "--subject"
             psychophysics run scenes/t4_2.json --out never)
mrh_cli_test(PsychophysicsRunBadStudyKeyExits2NamingIt 2 stderr
             "^mrh: error: .*t4_2\\.json: psychophysics\\.masses\\[0\\]"
             psychophysics run scenes/t4_2.json --subject A --out never --terminal
             --set "psychophysics.masses=[-5]")
mrh_cli_test(ValidateChecksTheStudyKeys 2 stderr
             "^mrh: error: .*t4_2\\.json: psychophysics\\.masses\\[0\\]"
             validate scenes/t4_2.json --set "psychophysics.masses=[-5]")
mrh_cli_test(ValidateAcceptsTheShippedStudy 0 stdout "^ok: " validate scenes/t4_2.json)
mrh_cli_test(PsychophysicsRunWithoutTheObjectExits2 2 stderr
             "^mrh: error: .*tiny\\.json: psychophysics = \\(missing\\)"
             psychophysics run ${fixtures}/tiny.json --subject A --out never --terminal)
mrh_cli_test(PsychophysicsAnalyzeBadTrialsExits2NamingTheFile 2 stderr
             "^mrh: error: .*tiny\\.json:1: no column"
             psychophysics analyze ${fixtures}/tiny.json --out never)

# Two trials (psychophysics_small.json: 2 masses x 1 trial) answered on standard input with the session's own (hand) device in real time.
set(psy_terminal_out ${CMAKE_CURRENT_BINARY_DIR}/psychophysics_terminal)
add_test(NAME cli.PsychophysicsTerminalRunRecordsTypedAnswers
         COMMAND ${expect} 0 stdout "^subject T: 2 of 2 trials answered \\(2 this run\\)" --
                 sh -c "rm -rf '${psy_terminal_out}' && printf '1\\n2\\n' | \"$0\" psychophysics run ${fixtures}/psychophysics_small.json --subject T --out '${psy_terminal_out}' --terminal"
                 ${mrh_bin}
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(cli.PsychophysicsTerminalRunRecordsTypedAnswers PROPERTIES LABELS apps
                     TIMEOUT 120)

if(TARGET mrh_viewer)
  # A person with a mouse in the study window under Xvfb, answering by (scripted) key presses.
  add_test(NAME viewer.PsychophysicsWindowSessionAnsweredByKeys
           COMMAND ${CMAKE_CURRENT_LIST_DIR}/psychophysics_window_test.sh ${mrh_bin}
                   ${fixtures}/psychophysics_small.json
                   ${CMAKE_CURRENT_BINARY_DIR}/psychophysics_window
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(viewer.PsychophysicsWindowSessionAnsweredByKeys
                       PROPERTIES LABELS viewer TIMEOUT 120 SKIP_RETURN_CODE 77
                                  ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0")
endif()
# Data from another tool with only the five columns the fit needs.
mrh_cli_test(PsychophysicsAnalyzeAcceptsFiveEssentialColumns 0 stdout "P1"
             psychophysics analyze ${fixtures}/five_column_trials.csv
             --out ${CMAKE_BINARY_DIR}/psychophysics_five_columns)
