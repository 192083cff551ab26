# SPDX-License-Identifier: Apache-2.0
# mrhaptics.load_session and methods(): the CLI's session semantics and its one-line errors.
import pytest

import mrhaptics
from conftest import run_cli

FIXTURES = "tests/apps/fixtures"


def cli_error(mrh_cli, *args):
    """The message `mrh ARGS` prints after "mrh: error: " (it must fail with exit code 2)."""
    done = run_cli(mrh_cli, *args, check=False)
    assert done.returncode == 2, done.stderr
    line = done.stderr.splitlines()[0]
    assert line.startswith("mrh: error: "), line
    return line[len("mrh: error: "):]


def test_methods_are_the_cli_methods(mrh_cli):
    listed = run_cli(mrh_cli, "methods").stdout.splitlines()
    names = [line.split()[0] for line in listed if line.startswith("  ") and line.strip()]
    assert mrhaptics.methods() == sorted(names)
    assert "local-dynamics" in mrhaptics.methods()


def test_overrides_reach_the_session(root):
    session = mrhaptics.load_session(root / "scenes/t4_1_impulse.json",
                                     {"method": "single-rate", "duration": 0.25,
                                      "device": {"type": "external"}})
    assert session.method == "single-rate"
    assert session.duration == 0.25
    assert session.device_type == "external"
    assert session.overrides == ["method=\"single-rate\"", "duration=0.25",
                                 "device={\"type\": \"external\"}"]
    assert session.scene.name == "t4_1.xml"


# (session file, overrides, the same as `mrh validate` --set arguments: a str value is JSON text
# in both, as Session.overrides shows)
LOAD_ERRORS = {
    "unknown key": (f"{FIXTURES}/unknown_key.json", None, []),
    "unknown override key": (f"{FIXTURES}/tiny.json", {"no_such_key": 1}, ["no_such_key=1"]),
    "wrong type": (f"{FIXTURES}/tiny.json", {"rendering.stiffness": "stiff"},
                   ['rendering.stiffness="stiff"']),
    "bad value": (f"{FIXTURES}/tiny.json", {"haptic_dt": -0.001}, ["haptic_dt=-0.001"]),
    "missing scene": (f"{FIXTURES}/missing_scene.json", None, []),
}


@pytest.mark.parametrize("name", sorted(LOAD_ERRORS))
def test_bad_input_raises_the_cli_message(name, mrh_cli):
    path, overrides, sets = LOAD_ERRORS[name]
    args = ["validate", path] + [a for s in sets for a in ("--set", s)]
    want = cli_error(mrh_cli, *args)
    with pytest.raises(ValueError) as error:
        session = mrhaptics.load_session(path, overrides)
        mrhaptics.run(session)  # a scene error shows when the world loads
    assert str(error.value) == want
    assert "\n" not in str(error.value)


def test_missing_file_is_a_value_error_naming_it():
    # The CLI's argument parser rejects a missing file before the session loader sees it.
    with pytest.raises(ValueError, match=r"^tests/apps/fixtures/no_such_session\.json: session "
                                         "file does not exist"):
        mrhaptics.load_session(f"{FIXTURES}/no_such_session.json")


def test_unknown_method_raises_the_cli_message_listing_methods(mrh_cli):
    want = cli_error(mrh_cli, "run", f"{FIXTURES}/tiny.json", "--set", 'method="no-such-method"')
    with pytest.raises(ValueError) as error:
        mrhaptics.load_session(f"{FIXTURES}/tiny.json", {"method": "no-such-method"})
    assert str(error.value) == want
    assert "impulse" in str(error.value)


@pytest.mark.parametrize("overrides", [{1: 2}, {"duration": float("nan")}, {"duration": object()}])
def test_overrides_that_are_not_json_raise_value_error(overrides):
    with pytest.raises(ValueError, match="load_session: override"):
        mrhaptics.load_session(f"{FIXTURES}/tiny.json", overrides)
