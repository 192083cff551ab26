# SPDX-License-Identifier: Apache-2.0
# mrhaptics.Engine: a Python servo loop pressing a sphere into a floor feels k·depth.
import math
import time

import numpy as np
import pytest

import mrhaptics

SESSION = "scenes/floor_external.json"
K = 1000.0      # N/m, rendering.stiffness of the session
RADIUS = 0.02   # m, the pointer sphere
# Force to this: k·depth is a few newtons; the penalty force is one product and a sum.
TOL = 1e-9


def pose_at_depth(depth):
    return [0.0, 0.0, RADIUS - depth, 1.0, 0.0, 0.0, 0.0]


@pytest.fixture
def session(root):
    return mrhaptics.load_session(root / SESSION)


@pytest.mark.parametrize("method", ["impulse", "single-rate", "local-dynamics"])
def test_tick_renders_k_times_depth_on_a_floor(root, method):
    session = mrhaptics.load_session(root / SESSION, {"method": method})
    ticks_per_hold = 100  # five 20 ms physics periods: the snapshot has seen the pose
    with mrhaptics.Engine(session) as engine:
        for depth in [0.001, 0.004, 0.0025]:
            for _ in range(ticks_per_hold):
                wrench = engine.tick(pose_at_depth(depth))
            assert wrench.shape == (6,) and wrench.dtype == np.float64
            assert wrench[2] == pytest.approx(K * depth, abs=TOL), (method, depth)
            assert np.abs(wrench[[0, 1, 3, 4, 5]]).max() <= TOL
        for _ in range(ticks_per_hold):
            wrench = engine.tick([0.0, 0.0, 0.05, 1.0, 0.0, 0.0, 0.0])  # lifted off
        assert np.abs(wrench).max() == 0.0
    assert engine.stats["ticks"] == 4 * ticks_per_hold
    assert engine.stats["faults"]["nonfinite_device"] == 0


def test_t_defaults_to_the_next_tick(session):
    with mrhaptics.Engine(session) as engine:
        assert engine.last_t is None
        engine.tick(pose_at_depth(0.0))
        assert engine.last_t == 0.0
        engine.tick(pose_at_depth(0.0))
        assert engine.last_t == engine.haptic_dt
        engine.tick(pose_at_depth(0.0), t=0.5)
        engine.tick(pose_at_depth(0.0))
        assert engine.last_t == 0.5 + engine.haptic_dt


def test_stop_returns_the_run_statistics(session):
    engine = mrhaptics.Engine(session)
    engine.start()
    for _ in range(60):
        engine.tick(pose_at_depth(0.002))
    stats = engine.stop()
    assert stats is engine.stats
    assert stats["ticks"] == 60
    assert stats["method"] == "impulse" and stats["mode"] == "lockstep"
    assert stats["max_force"] == pytest.approx(2.0, abs=TOL)
    assert not engine.running


BAD_POSES = {
    "nan": [0, 0, 0.01, math.nan, 0, 0, 0],
    "inf": [0, 0, math.inf, 1, 0, 0, 0],
    "short": [0, 0, 0.01],
    "2-d": [[0, 0, 0.01, 1, 0, 0, 0]],
    "not numbers": ["a", "b", "c", "d", "e", "f", "g"],
    "zero quaternion": [0, 0, 0.01, 0, 0, 0, 0],
    "non-unit quaternion": [0, 0, 0.01, 2, 0, 0, 0],
}


@pytest.mark.parametrize("name", sorted(BAD_POSES))
def test_bad_pose_is_a_value_error_and_reaches_no_device(session, name):
    with mrhaptics.Engine(session) as engine:
        for _ in range(40):
            engine.tick(pose_at_depth(0.003))
        with pytest.raises(ValueError, match="Engine.tick: pose"):
            engine.tick(BAD_POSES[name])
        wrench = engine.tick(pose_at_depth(0.003))
        assert wrench[2] == pytest.approx(K * 0.003, abs=TOL)
    assert engine.stats["ticks"] == 41
    assert engine.stats["faults"]["nonfinite_device"] == 0


@pytest.mark.parametrize("velocity", [[0.0] * 5, [math.nan] + [0.0] * 5])
def test_bad_velocity_is_a_value_error(session, velocity):
    with mrhaptics.Engine(session) as engine:
        with pytest.raises(ValueError, match="Engine.tick: velocity"):
            engine.tick(pose_at_depth(0.0), velocity=velocity)


@pytest.mark.parametrize("t", [math.nan, -1.0, 0.0])
def test_time_must_be_finite_and_increase(session, t):
    with mrhaptics.Engine(session) as engine:
        engine.tick(pose_at_depth(0.0), t=0.0)
        with pytest.raises(ValueError, match="Engine.tick: t ="):
            engine.tick(pose_at_depth(0.0), t=t)


def test_engine_needs_an_external_device(root):
    session = mrhaptics.load_session(root / "scenes/t4_1_impulse.json")
    with pytest.raises(ValueError, match='device.type = "fixed"; Engine needs "external"'):
        mrhaptics.Engine(session)


def test_tick_outside_a_run_is_a_runtime_error(session):
    engine = mrhaptics.Engine(session)
    with pytest.raises(RuntimeError, match="start"):
        engine.tick(pose_at_depth(0.0))
    engine.start()
    with pytest.raises(RuntimeError, match="already started"):
        engine.start()
    engine.stop()
    with pytest.raises(RuntimeError, match="stopped"):
        engine.tick(pose_at_depth(0.0))


def test_realtime_engine_renders_the_floor(root):
    # The physics thread steps beside this loop; a loaded machine may stall it (the watchdog then
    # fades the force), so the test asks for k·depth on some tick, not on every one.
    session = mrhaptics.load_session(root / SESSION, {"mode": "realtime"})
    forces = []
    with mrhaptics.Engine(session) as engine:
        for _ in range(2000):
            forces.append(engine.tick(pose_at_depth(0.002))[2])
            if abs(forces[-1] - K * 0.002) <= TOL:
                break
            time.sleep(0.0005)
    assert abs(forces[-1] - K * 0.002) <= TOL, max(forces)
    assert engine.stats["mode"] == "realtime"
