# SPDX-License-Identifier: Apache-2.0
# `mrh ir`: the IR as JSON, and its one-line errors (included by tests/apps/CMakeLists.txt).
set(ir_session scenes/cube_on_floor.json)

mrh_cli_test(IrHelpShowsExamples 0 stdout "^Examples:" ir --help)
# Face case (thesis §3.2.1): the 0.2 m cube 5 mm into the floor gives exactly 4 contacts, and
# touches nothing else (the other objects are 0.5 m away).
mrh_cli_test(IrFaceOnFloorPrintsFourContacts 0 stdout
             "^\\{\"pairs\":\\[\\{\"object\":\"floor\",[^]]*\\],\"plane_point\":\\[[^]]*\\],\"contacts\":\\[(\\[[^]]*\\],){3}\\[[^]]*\\]\\],\"depths\":\\[[^]]*\\][^]]*\\}\\],\"status\":\\[\\]\\}$"
             ir ${ir_session} --pose 0 0 0.095 1 0 0 0)
mrh_cli_test(IrFarFromEverythingPrintsNoPairs 0 stdout "^\\{\"pairs\":\\[\\],\"status\":\\[\\]\\}$"
             ir ${ir_session} --pose 0 0 0.3 1 0 0 0)
# --pose follows the session's rule: any nonzero quaternion, normalised.
mrh_cli_test(IrNonUnitQuaternionIsNormalised 0 stdout "^\\{\"pairs\":"
             ir ${ir_session} --pose 0 0 0.3 0.99999 0 0 0)
mrh_cli_test(IrZeroQuaternionExits2 2 stderr
             "^mrh: error: --pose: quaternion .* has \\(almost\\) zero norm. expected a rotation"
             ir ${ir_session} --pose 0 0 0.1 0 0 0 0)
mrh_cli_test(IrTooFewPoseNumbersExits2 2 stderr "^mrh: error: .*--pose"
             ir ${ir_session} --pose 0 0 0.1)
mrh_cli_test(IrMissingPoseExits2 2 stderr "^mrh: error: .*--pose" ir ${ir_session})
mrh_cli_test(IrMissingSessionExits2NamingIt 2 stderr "^mrh: error: .*no_such_session\\.json"
             ir no_such_session.json --pose 0 0 0.1 1 0 0 0)
# Edge case (thesis §3.2.1): the cube turned 45° about x with its lowest edge 5 mm into the floor
# gives exactly 2 contacts (the ends of the buried edge).
mrh_cli_test(IrEdgeOnFloorPrintsTwoContacts 0 stdout
             "^\\{\"pairs\":\\[\\{\"object\":\"floor\",[^]]*\\],\"plane_point\":\\[[^]]*\\],\"contacts\":\\[\\[[^]]*\\],\\[[^]]*\\]\\],\"depths\":\\[[^]]*\\][^]]*\\}\\],\"status\":\\[\\]\\}$"
             ir ${ir_session} --pose 0 0 0.1364213562373095 0.9238795325112867 0.3826834323650898 0 0)
