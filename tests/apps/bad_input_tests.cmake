# SPDX-License-Identifier: Apache-2.0
# Every reproducer of bad input exits 2 with ONE line naming the file and the key (or
# runs correctly). Included by tests/apps/CMakeLists.txt (mrh_bin, fixtures, mrh_cli_test).
set(one_line ${CMAKE_CURRENT_SOURCE_DIR}/expect_one_line.sh)
set(bad ${fixtures}/bad)

# bad_input_test(NAME REGEX ARGS...): `mrh ARGS` exits 2 with one stderr line matching REGEX.
function(bad_input_test name regex)
  add_test(NAME cli.bad.${name} COMMAND ${one_line} 2 ${regex} -- ${mrh_bin} ${ARGN}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.bad.${name} PROPERTIES LABELS apps TIMEOUT 60)
endfunction()

set(impulse scenes/t4_1_impulse.json)
set(local scenes/t4_1_local.json)
set(cube scenes/cube_on_floor.json)
set(err "^mrh: error: ")

# SIGFPE: ticks per step 0 or 2^32.
bad_input_test(TinyHapticDt "${err}scenes/t4_1_impulse\\.json: haptic_dt = 1e-300 s. expected"
               run ${impulse} --set haptic_dt=1e-300)
bad_input_test(HugePhysicsDt "${err}scenes/t4_1_impulse\\.json: physics_dt = 4294967\\.296 s"
               run ${impulse} --set physics_dt=4294967.296 --set safety.watchdog_timeout=1e8)
# SIGABRT in the perturbation measurement.
bad_input_test(HugePerturbationForce
               "${err}scenes/t4_1_local\\.json: rendering\\.perturbation_force = 1e\\+300 N"
               run ${local} --set rendering.perturbation_force=1e300)
bad_input_test(DenormalPerturbationForce
               "${err}scenes/t4_1_local\\.json: rendering\\.perturbation_force = 5e-324 N"
               validate ${local} --set rendering.perturbation_force=5e-324)
bad_input_test(HugePointerRadius "${err}scenes/t4_1_local\\.json: pointer\\.radius = 1e\\+300 m"
               run ${local} --set pointer.radius=1e300)
bad_input_test(HugeGravity "${err}scenes/t4_1_local\\.json: gravity: \\[0, 0, -1e\\+308\\]"
               run ${local} --set "gravity=[0,0,-1e308]")
bad_input_test(SceneInfPosition "${err}.*inf_pos\\.xml: body 'cube' pos = \\[0, -inf, 0\\.05\\] m"
               run ${bad}/inf_pos.json)
# SIGABRT in FCL's GJK.
bad_input_test(HugeSideGravity "${err}scenes/cube_on_floor\\.json: gravity: \\[1e\\+300, 0, 0\\]"
               run ${cube} --set "gravity=[1e300,0,0]")
bad_input_test(SceneNanGravity "${err}.*nan_gravity\\.xml: <option gravity> = \\[0, nan, -9\\.81\\]"
               validate ${bad}/nan_gravity.json)
bad_input_test(SceneHugeGeomSize "${err}.*huge_size\\.xml: geom #1 size = \\[1e\\+300, 1e\\+300, 1e\\+300\\] m"
               validate ${bad}/huge_size.json)
# Hang: 2e11 ticks.
bad_input_test(PicoHapticDt "${err}scenes/t4_1_impulse\\.json: haptic_dt = 1e-12 s"
               run ${impulse} --set physics_dt=0.1 --set haptic_dt=1e-12
               --set safety.watchdog_timeout=1)
# Exit 0 with nothing run.
bad_input_test(HugeDuration "${err}scenes/t4_1_impulse\\.json: duration = 1e\\+300 s. expected"
               run ${impulse} --duration 1e300)
bad_input_test(SubTickDuration "${err}scenes/t4_1_impulse\\.json: duration = 1e-04 s. expected a finite value in \\[0\\.001, 3600\\] s"
               run ${impulse} --duration 1e-4)
# Accepted, then the force held at 0: device data checked at load, replay as scripted.
bad_input_test(ReplayHugeQuaternion
               "${err}.*replay_quat\\.csv:3: columns .*quaternion \\(qw, qx, qy, qz\\) = \\(1e\\+200"
               validate ${bad}/replay_quat.json)
bad_input_test(KeyframesDenormalApart
               "${err}scenes/demo\\.json: device\\.keyframes\\[1\\]: t = 5e-324 s is not 1e-06 s"
               validate scenes/demo.json --set
               "device.keyframes=[[0,0,0,0.3,1,0,0,0],[5e-324,0,0,0.3,1,0,0,0]]")
bad_input_test(HugeFixedPosition "${err}scenes/cube_on_floor\\.json: device\\.pose: position x = 1e\\+308 m"
               validate ${cube} --set "device.pose=[1e308,0,0.3,1,0,0,0]")
bad_input_test(TinyHandMass "${err}scenes/demo\\.json: device\\.hand\\.mass = 1e-300 kg"
               validate scenes/demo.json --set device.hand.mass=1e-300)
bad_input_test(StiffHand "${err}scenes/demo\\.json: device\\.hand\\.stiffness = 2e\\+09 N/m"
               validate scenes/demo.json --set device.hand.stiffness=2e9)
bad_input_test(UnstableHand "${err}scenes/demo\\.json: device\\.hand\\.stiffness = 9e\\+05 with device\\.hand\\.mass = 0\\.5 makes the simulated hand unstable"
               validate scenes/demo.json --set device.hand.stiffness=9e5)
bad_input_test(HugeCalibrationScale "${err}scenes/demo\\.json: device\\.calibration\\.scale: 1e\\+300"
               validate scenes/demo.json --set device.calibration.scale=1e300)
# Messages.
foreach(kind equal collinear coplanar)
  bad_input_test(DegenerateMesh_${kind} "${err}.*mesh_${kind}\\.xml: "
                 validate ${bad}/mesh_${kind}.json)
endforeach()
bad_input_test(SetWithoutEqualsNamesTheFile "${err}scenes/cube_on_floor\\.json: --set physics_dt: missing '='"
               validate ${cube} --set physics_dt)
bad_input_test(RadiusMissingFor3Dof
               "${err}.*box_pointer\\.xml: pointer\\.body = 'pointer' has no sphere geom and pointer\\.radius is not set"
               validate ${bad}/box_pointer.json --set method=impulse)
bad_input_test(UnknownMethodNamesFileAndSuggests
               "${err}scenes/cube_on_floor\\.json: method: unknown method \"impuls\" .*did you mean \"impulse\""
               validate ${cube} --set method=impuls)
bad_input_test(DenormalRotationWeight
               "${err}scenes/cube_on_floor\\.json: rendering\\.rotation_weight = \\[1e-320, 1, 1\\] m\\^2"
               validate ${cube} --set method=proxy-6dof --set "rendering.rotation_weight=[1e-320,1,1]")
bad_input_test(HugeWatchdog "${err}scenes/cube_on_floor\\.json: safety\\.watchdog_timeout = 1e\\+308 s"
               validate ${cube} --set safety.watchdog_timeout=1e308)
bad_input_test(NulInString "${err}.*tiny_scene\\.xml: pointer body 'a\\\\x00b' not found"
               validate ${bad}/nul_string.json)
bad_input_test(HugeQuaternionIsNotZero
               "${err}scenes/cube_on_floor\\.json: device\\.pose: quaternion \\(qw, qx, qy, qz\\) = \\(1e\\+200, 0, 0, 0\\) .*expected finite"
               validate ${cube} --set "device.pose=[0,0,0.3,1e200,0,0,0]")
bad_input_test(OverflowingNumberIsANumber
               "${err}scenes/cube_on_floor\\.json: device\\.limits\\.max_force: found a number \\(inf\\)"
               validate ${cube} --set device.limits.max_force=1e309)
bad_input_test(PointerBodyNotFoundNamesTheKey
               "${err}.*cube_on_floor\\.xml: pointer body 'nosuch' not found. .*set pointer\\.body in the session"
               validate ${cube} --set pointer.body=nosuch)

# Runs correctly: a 6-DOF method needs no pointer radius; a concave mesh is hulled with a warning.
mrh_cli_test(ProxyRunsWithoutPointerRadius 0 stdout "^ok: " validate ${bad}/box_pointer.json)
mrh_cli_test(ConcaveMeshWarns 0 stderr "^mrh: warning: .*concave_mesh\\.xml: mesh 'L' .*convex hull"
             run ${bad}/concave_mesh.json --quiet --out ${CMAKE_CURRENT_BINARY_DIR}/concave_out)

# Divergence is a fault: exit 1 with one line naming the scene, the body and the time.
function(diverged_test name regex)
  add_test(NAME cli.diverged.${name} COMMAND ${one_line} 1 ${regex} -- ${mrh_bin} ${ARGN}
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(cli.diverged.${name} PROPERTIES LABELS apps TIMEOUT 60)
endfunction()
diverged_test(StiffSpringResetsTheState
              "${err}.*diverging_scene\\.xml: the simulation diverged at t = .* bad number in .* body 'arm'.*likely causes"
              run ${fixtures}/diverging.json --out ${CMAKE_BINARY_DIR}/cli_diverged_spring)
# The records up to the fault stay. The thrown ball (30 m/s) under gravity passes 40 m/s at
# t = sqrt(40^2 - 30^2) / 9.81 = 2.697 s: 134 steps of 20 ms and 2680 ticks precede the fault.
add_test(NAME cli.diverged.RecordsUpToTheFaultAreKept
         COMMAND sh -c "rm -rf \"$1\" && \"$0\" run ${fixtures}/thrown.json --out \"$1\" -q \
--set safety.max_body_speed=40 --set 'gravity=[0,0,-9.81]' --set duration=4; \
test $? -eq 1 && test $(wc -l < \"$1/steps.csv\") -gt 130 && \
test $(wc -l < \"$1/ticks.csv\") -gt 2600"
                 ${mrh_bin} ${CMAKE_BINARY_DIR}/cli_diverged_records
         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
set_tests_properties(cli.diverged.RecordsUpToTheFaultAreKept PROPERTIES LABELS apps TIMEOUT 60)
diverged_test(BodyFasterThanMaxBodySpeed
              "${err}.*thrown_scene\\.xml: the simulation diverged at t = 0\\.02 s: body 'ball' moves at 30 m/s, over safety\\.max_body_speed = 20 m/s"
              run ${fixtures}/thrown.json --out ${CMAKE_BINARY_DIR}/cli_diverged_thrown)
# The guard can be raised: the same throw then runs to the end.
mrh_cli_test(MaxBodySpeedRaisedLetsTheThrowRun 0 stdout "^summary: "
             run ${fixtures}/thrown.json --set safety.max_body_speed=50
             --out ${CMAKE_BINARY_DIR}/cli_thrown_allowed)

# A scene's relative asset paths resolve against the scene's folder for every method, the
# virtual-coupling tool's rewritten scene included (run from the project root, not that folder).
foreach(method virtual-coupling local-dynamics proxy-6dof)
  mrh_cli_test(RelativeMeshAssetLoadsFromAnotherFolder_${method} 0 stdout "^summary: "
               run ${fixtures}/mesh_asset.json --method ${method}
               --out ${CMAKE_BINARY_DIR}/cli_mesh_asset_${method})
endforeach()

# Errors of the engine's own checks name the file to edit: the session for a
# settings conflict, the scene for a massless 6-DOF pointer.
bad_input_test(WatchdogShorterThanTwoStepsNamesTheSession
               "${err}tests/apps/fixtures/tiny\\.json: safety\\.watchdog_timeout = 0\\.01 s must exceed"
               run ${fixtures}/tiny.json --set safety.watchdog_timeout=0.01)
bad_input_test(MasslessPointerNamesTheScene
               "${err}.*massless_pointer_scene\\.xml: pointer body 'pointer' has mass 0 kg"
               run ${fixtures}/massless_pointer.json)

# A real device in lockstep mode never gets an answer; the session is refused.
bad_input_test(UdpDeviceInLockstepNamesTheModeToUse
               "${err}tests/apps/fixtures/tiny\\.json: mode: \"lockstep\" with the real device \"udp\".*expected \"realtime\".*--mode realtime"
               run ${fixtures}/tiny.json --mode lockstep --set "device={\"type\": \"udp\"}")

# The compound (non-convex) example scene runs as shipped.
mrh_cli_test(CompoundMugSessionRuns 0 stdout "^summary: "
             run scenes/compound_mug.json --out ${CMAKE_BINARY_DIR}/cli_compound_mug)
