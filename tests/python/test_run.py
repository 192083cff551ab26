# SPDX-License-Identifier: Apache-2.0
# mrhaptics.run against `mrh run`: the same session gives the same numbers, bit for bit in
# lockstep, and `out` writes the CLI's files.
import json

import numpy as np
import pytest

import mrhaptics
from conftest import assert_columns_equal, read_csv, run_cli

# Short lockstep runs with contact and moving bodies, each with a --set override:
# (session file, overrides as load_session takes them, the same as `mrh run --set` arguments).
CASES = {
    "impulse": ("scenes/t4_1_impulse.json", {"duration": 0.6, "rendering.stiffness": 1500},
                ["duration=0.6", "rendering.stiffness=1500"]),
    "local-dynamics": ("scenes/compound_mug.json", {"duration": 1.2}, ["duration=1.2"]),
    "proxy-6dof": ("scenes/t3_6_push.json", {"duration": 2.0}, ["duration=2.0"]),
}

# The summary's keys that do not depend on the wall clock.
DETERMINISTIC_KEYS = ["method", "mode", "physics_dt", "haptic_dt", "sim_time", "ticks", "steps",
                      "max_force", "max_torque", "faults", "final_wrench", "impulses",
                      "method_status", "warnings"]


@pytest.fixture(scope="module", params=sorted(CASES))
def case(request, root, mrh_cli, tmp_path_factory):
    """One session run by the CLI (its files) and by run() (with out=)."""
    path, overrides, sets = CASES[request.param]
    cli_dir = tmp_path_factory.mktemp("cli")
    args = ["run", path, "--mode", "lockstep", "--quiet", "--out", cli_dir]
    for s in sets:
        args += ["--set", s]
    run_cli(mrh_cli, *args)
    py_dir = tmp_path_factory.mktemp("py")
    session = mrhaptics.load_session(root / path, overrides)
    result = mrhaptics.run(session, out=py_dir)
    return cli_dir, py_dir, result


def test_ticks_equal_the_cli_ticks_csv_bit_for_bit(case):
    cli_dir, _, result = case
    want = read_csv(cli_dir / "ticks.csv")
    assert_columns_equal(result.ticks, want)
    assert result.ticks["contacts"].dtype == np.int64
    assert np.abs(result.ticks["fx"]).max() > 0.0 or np.abs(result.ticks["fz"]).max() > 0.0


def test_bodies_equal_the_cli_bodies_csv_bit_for_bit(case):
    cli_dir, _, result = case
    want = read_csv(cli_dir / "bodies.csv")
    assert len(want["t"]) > 0
    assert_columns_equal(result.bodies, want)


def test_steps_equal_the_cli_steps_csv_except_wall_clock_timings(case):
    cli_dir, _, result = case
    want = read_csv(cli_dir / "steps.csv")
    assert list(result.steps) == list(want)
    assert_columns_equal(result.steps, want, columns=["t", "step", "sim_contacts", "neighbors",
                                                      "point_contacts", "solver_iterations"])


def test_summary_equals_the_cli_summary_json(case):
    cli_dir, _, result = case
    want = json.loads((cli_dir / "summary.json").read_text())
    assert list(result.summary) == list(want)
    for key in DETERMINISTIC_KEYS:
        assert result.summary[key] == want[key], key


def test_out_writes_the_cli_files(case):
    cli_dir, py_dir, _ = case
    for name in ["ticks.csv", "bodies.csv"]:
        assert (py_dir / name).read_bytes() == (cli_dir / name).read_bytes(), name
    summary = json.loads((py_dir / "summary.json").read_text())
    want = json.loads((cli_dir / "summary.json").read_text())
    assert {k: summary[k] for k in DETERMINISTIC_KEYS} == {k: want[k] for k in DETERMINISTIC_KEYS}
    assert (py_dir / "steps.csv").is_file()
    assert (py_dir / "report.png").is_file() == (cli_dir / "report.png").is_file()


def test_mode_overrides_the_session_mode(root):
    session = mrhaptics.load_session(root / "scenes/t4_1_impulse.json",
                                     {"mode": "realtime", "duration": 0.1})
    assert session.mode == "realtime"
    assert mrhaptics.run(session).summary["mode"] == "lockstep"
    realtime = mrhaptics.run(session, mode="realtime")
    assert realtime.summary["mode"] == "realtime"
    assert len(realtime.ticks["t"]) == realtime.summary["ticks"] > 0


def test_bad_mode_is_a_value_error(root):
    session = mrhaptics.load_session(root / "scenes/t4_1_impulse.json")
    with pytest.raises(ValueError, match="mode = 'sometimes'"):
        mrhaptics.run(session, mode="sometimes")
