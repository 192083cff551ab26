# SPDX-License-Identifier: Apache-2.0
# Several pointers through `mrh run`: scenes/two_finger_grasp.json lifts the box with
# two fingertips; ticks.csv names each row's pointer and summary.json has a block per pointer;
# a bad element is one line naming it, exit 2.
import csv
import json

from conftest import run_cli


def test_two_fingers_lift_the_box_and_name_their_rows(mrh_cli, tmp_path):
    run_cli(mrh_cli, "run", "scenes/two_finger_grasp.json", "--quiet", "--out", tmp_path)
    with open(tmp_path / "ticks.csv", newline="") as file:
        rows = list(csv.reader(file))
    assert rows[0][-1] == "pointer"
    assert [row[-1] for row in rows[1:5]] == ["thumb", "index", "thumb", "index"]
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert [p["body"] for p in summary["pointers"]] == ["thumb", "index"]
    assert len(rows) - 1 == 2 * summary["ticks"]
    # The box (resting with its centre at 3 cm) is held above 7 cm during the hold (1.2-2.0 s).
    with open(tmp_path / "bodies.csv", newline="") as file:
        bodies = list(csv.DictReader(file))
    held = [float(b["z"]) for b in bodies if b["body"] == "box" and 1.2 <= float(b["t"]) <= 2.0]
    assert held and min(held) > 0.07


def test_a_bad_pointer_device_is_one_line_naming_the_element(mrh_cli):
    bad = ('pointers=[{"body": "thumb", "device": {"type": "fixed", "pose": [0,0,0,1,0,0,0]}},'
           ' {"body": "index", "device": {"type": "glove"}}]')
    done = run_cli(mrh_cli, "run", "scenes/two_finger_grasp.json", "--set", bad, check=False)
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and "pointers[1].device.type" in lines[0]


def test_a_method_of_one_pointer_refuses_several(mrh_cli):
    done = run_cli(mrh_cli, "run", "scenes/two_finger_grasp.json", "--set",
                   "method=penalty-sum", check=False)
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and 'method = "penalty-sum" renders one' in lines[0]
