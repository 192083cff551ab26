#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Mutation fuzzer of mrh's inputs: sessions (JSON), scenes (MJCF) and CSV trajectories.

Each case takes one shipped file (scenes/, tests/apps/fixtures/), mutates it (wrong types,
extreme numbers incl. denormals and 1e308, inf/NaN, truncation, binary junk, duplicate keys,
deep nesting, bad --set values), then runs `mrh validate` and a short `mrh run` on it and checks:

  * the exit code is 0 or 2 and no signal ended the process; a run may also exit 1 when the
    simulation diverged (a runtime fault, one line "mrh: error: <file>: the simulation
    diverged at t = ...": validate cannot foresee it);
  * each call ends within --timeout seconds;
  * exit 2 prints exactly one line, "mrh: error: <file>: ...", <file> being one of the case's
    files (session, scene or CSV, with :line allowed);
  * exit 0 prints nothing but mrh's own lines (no qhull/MuJoCo/FCL output) and a run records
    at least one tick (no silent no-op);
  * `mrh validate` accepts exactly what `mrh run` can run (validate 0 => run 0, 2 => 2).

Usage: fuzz.py --mrh build/bin/mrh [--cases 300] [--seed 1] [--timeout 30] [--keep DIR]
Exit status: 0 if every case passed, 1 otherwise (failing cases are kept in --keep).
Standard library only.
"""
import argparse
import concurrent.futures
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

EXTREME_NUMBERS = [0, -0.0, 5e-324, 2.2250738585072014e-308, 1e-300, 1e-12, -1, -1e-9, 1e-5,
                   1e300, 1e308, -1e308, 1.7976931348623157e308, 4294967.296, 2**31, 2**53 + 1,
                   1e20, 0.999999, 3, 1e6]
# Text-level number tokens JSON itself cannot hold (the parser must reject them, one line).
BAD_NUMBER_TOKENS = ["NaN", "Infinity", "-Infinity", "1e309", "-1e309", "nan", "inf", "0x10",
                     "1e-400", "00.5", "+1", ".5"]
XML_NUMBERS = ["nan", "NaN", "inf", "-inf", "1e308", "-1e308", "1e300", "5e-324", "1e-300", "0",
               "-1", "-0", "1e20", "abc", "", "1 2", "0x1p3", "4e38"]
CSV_FIELDS = ["nan", "inf", "-inf", "1e308", "-1e308", "5e-324", "1e200", "", "x", "0", "-0",
              "1e-300", "1e309", "0,0", "\"1\""]
JUNK = [b"\x00", b"\xff\xfe", b"\x1b[2J", b"\x00\x01\x02\x03", "é".encode(), b"\r", b"\n\n",
        b"{", b"}", b"]", b"<", b"\"", b"\\"]
SET_KEYS = ["haptic_dt", "physics_dt", "duration", "method", "mode", "gravity", "keyframe",
            "pointer.radius", "pointer.body", "rendering.stiffness", "rendering.damping",
            "rendering.neighbor_distance", "rendering.neighbor_margin",
            "rendering.curved_segments", "rendering.rot_stiffness", "rendering.rot_damping",
            "rendering.rotation_weight", "rendering.rotation_weight_scale", "rendering.friction",
            "rendering.proxy_solver", "rendering.max_iterations", "rendering.solver_tolerance",
            "rendering.perturbation", "rendering.perturbation_force", "safety.ramp",
            "safety.ramp_time", "safety.watchdog_timeout", "safety.watchdog_fade",
            "device.limits.max_force", "device.limits.max_torque", "device.limits.max_stiffness",
            "device.calibration.scale", "device.calibration.position",
            "device.calibration.orientation", "device.hand.mass", "device.hand.stiffness",
            "device.hand.damping", "device.hand.inertia", "device", "device.pose",
            "device.type", "realtime_priority"]
METHODS = ["impulse", "local-dynamics", "proxy-6dof", "single-rate"]
RUN_DURATION = "0.03"  # s: every run is short; validate gets the same value


def rand_number(rng):
    x = rng.choice(EXTREME_NUMBERS)
    return -x if rng.random() < 0.2 and isinstance(x, float) else x


def rand_value(rng, depth=0):
    kind = rng.randrange(9)
    if kind == 0:
        return rand_number(rng)
    if kind == 1:
        return rng.choice(["", "x", "a\u0000b", "é" * 3, "impulse", "proxy-6dof", "pointer",
                           "../../etc/passwd", "/dev/null", "scenes", "1e308"])
    if kind == 2:
        return rng.choice([True, False, None])
    if kind == 3 and depth < 3:
        return [rand_value(rng, depth + 1) for _ in range(rng.randrange(9))]
    if kind == 4 and depth < 3:
        return {rng.choice(["x", "type", "pose", "mass", "scene"]): rand_value(rng, depth + 1)}
    if kind == 5:
        return [rand_number(rng) for _ in range(rng.choice([3, 4, 7, 8]))]
    if kind == 6:
        return [rng.choice([0, 1, 1e200, 5e-324, -1]) for _ in range(7)]
    return rand_number(rng)


def json_paths(value, path=()):
    yield path
    if isinstance(value, dict):
        for k, v in value.items():
            yield from json_paths(v, path + (k,))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from json_paths(v, path + (i,))


def set_at(doc, path, value):
    if not path:
        return value
    target = doc
    for p in path[:-1]:
        target = target[p]
    target[path[-1]] = value
    return doc


def mutate_bytes(rng, data):
    """Truncation, junk insertion, byte flips, duplication of a slice."""
    data = bytearray(data)
    op = rng.randrange(4)
    if op == 0 and data:
        del data[rng.randrange(len(data)):]
    elif op == 1:
        at = rng.randrange(len(data) + 1)
        data[at:at] = rng.choice(JUNK) * rng.randrange(1, 4)
    elif op == 2 and data:
        for _ in range(rng.randrange(1, 6)):
            data[rng.randrange(len(data))] = rng.randrange(256)
    elif data:
        a = rng.randrange(len(data))
        b = min(len(data), a + rng.randrange(1, 200))
        at = rng.randrange(len(data) + 1)
        data[at:at] = data[a:b]
    return bytes(data)


def mutate_json(rng, text):
    """Returns (new text, extra --set overrides)."""
    op = rng.randrange(10)
    if op <= 3:
        doc = json.loads(text)
        paths = list(json_paths(doc))
        path = rng.choice(paths[1:]) if len(paths) > 1 else ()
        doc = set_at(doc, path, rand_value(rng))
        return json.dumps(doc), []
    if op == 4:
        doc = json.loads(text)
        paths = [p for p in json_paths(doc) if p]
        path = rng.choice(paths)
        parent = doc
        for p in path[:-1]:
            parent = parent[p]
        del parent[path[-1]]
        return json.dumps(doc), []
    if op == 5:  # a number token JSON cannot hold, or a duplicate key
        if rng.random() < 0.5:
            numbers = list(re.finditer(rb"-?\d+(\.\d+)?([eE][-+]?\d+)?", text.encode()))
            if numbers:
                m = rng.choice(numbers)
                b = text.encode()
                return (b[:m.start()] + rng.choice(BAD_NUMBER_TOKENS).encode() +
                        b[m.end():]).decode("utf-8", "replace"), []
        key = rng.choice(["method", "haptic_dt", "scene", "device", "duration"])
        value = json.dumps(rand_value(rng))
        return text.replace("{", "{" + json.dumps(key) + ": " + value + ", ", 1), []
    if op == 6:  # deep nesting
        depth = rng.choice([100, 1000, 100000])
        doc = json.loads(text)
        key = rng.choice(["device", "rendering", "gravity", "pointer", "scene"])
        nested = "[" * depth + "1" + "]" * depth if rng.random() < 0.5 else \
            '{"a":' * depth + "1" + "}" * depth
        doc[key] = "@@NEST@@"
        return json.dumps(doc).replace('"@@NEST@@"', nested), []
    if op == 7:
        return mutate_bytes(rng, text.encode()).decode("utf-8", "surrogateescape"), []
    # --set overrides, 1 to 3 of them
    sets = []
    for _ in range(rng.randrange(1, 4)):
        key = rng.choice(SET_KEYS)
        if key == "method":
            value = rng.choice(METHODS + ["x", "", "impuls"])
        elif rng.random() < 0.15:
            value = rng.choice(["", "1e309", "NaN", "[1,2", "{}", "[]", "null", "true"])
        else:
            value = json.dumps(rand_value(rng))
        sets.append(f"{key}={value}" if rng.random() < 0.95 else key)
    return text, sets


def mutate_xml(rng, text):
    op = rng.randrange(6)
    if op <= 2:  # a numeric attribute value
        attrs = list(re.finditer(r'(pos|size|mass|gravity|quat|euler|friction|timestep|density|'
                                 r'vertex|fromto|axisangle|inertia|diaginertia)="([^"]*)"', text))
        if attrs:
            m = rng.choice(attrs)
            parts = m.group(2).split()
            if parts:
                parts[rng.randrange(len(parts))] = rng.choice(XML_NUMBERS)
            return text[:m.start(2)] + " ".join(parts) + text[m.end(2):]
    if op == 3:  # deep nesting of bodies
        depth = rng.choice([50, 500])
        nest = "".join(f'<body name="n{i}" pos="0 0 0.01">' for i in range(depth))
        nest += '<geom type="sphere" size="0.01"/>' + "</body>" * depth
        return text.replace("</worldbody>", nest + "</worldbody>", 1)
    if op == 4:  # degenerate meshes: equal, collinear or coplanar points
        vertex = rng.choice(["0 0 0  0 0 0  0 0 0  0 0 0", "0 0 0  1 0 0  2 0 0  3 0 0",
                             "0 0 0  1 0 0  0 1 0  1 1 0", "0 0 0  1e300 0 0  0 1 0  0 0 1",
                             "0 0 0  0.1 0 0  0 0.1 0  0 0 0.1  0.1 0.1 0.1  0.05 0.05 0.2"])
        asset = f'<asset><mesh name="fuzzmesh" vertex="{vertex}"/></asset>'
        geom = '<body name="fuzzbody" pos="0.3 0.3 0.1"><freejoint/>' \
               '<geom type="mesh" mesh="fuzzmesh" mass="0.1"/></body>'
        text = re.sub(r"(<mujoco[^>]*>)", r"\1" + asset, text, count=1)
        return text.replace("</worldbody>", geom + "</worldbody>", 1)
    return mutate_bytes(rng, text.encode()).decode("utf-8", "surrogateescape")


def mutate_csv(rng, text):
    lines = text.splitlines()
    op = rng.randrange(5)
    if op <= 1 and len(lines) > 1:
        i = rng.randrange(1, len(lines))
        fields = lines[i].split(",")
        fields[rng.randrange(len(fields))] = rng.choice(CSV_FIELDS)
        lines[i] = ",".join(fields)
    elif op == 2 and len(lines) > 2:
        i = rng.randrange(1, len(lines))
        lines.insert(i, lines[i] if rng.random() < 0.5 else lines[rng.randrange(1, len(lines))])
    elif op == 3 and len(lines) > 1:  # keyframes 5e-324 s apart, or quaternions of 1e200
        i = rng.randrange(1, len(lines))
        fields = lines[i].split(",")
        if rng.random() < 0.5 and len(fields) > 4:
            fields[4:8] = ["1e200", "0", "0", "0"][:len(fields[4:8])]
        else:
            fields[0] = repr(float(lines[i - 1].split(",")[0] or 0) + 5e-324) if i > 1 else "0"
        lines[i] = ",".join(fields)
    else:
        return mutate_bytes(rng, text.encode()).decode("utf-8", "surrogateescape")
    return "\n".join(lines) + "\n"


class Case:
    def __init__(self, index, kind, source, files, sets, session):
        self.index, self.kind, self.source = index, kind, source
        self.files, self.sets, self.session = files, sets, session


def make_case(rng, index, root, work):
    """Writes the mutated file(s) of one case into `work` (a copy of the corpus folders)."""
    sessions = sorted((work / "scenes").glob("*.json")) + \
        sorted((work / "fixtures").glob("*.json"))
    sessions = [s for s in sessions if "fuzz_" not in s.name]
    kind = rng.choices(["session", "scene", "csv"], weights=[6, 3, 1])[0]
    base = rng.choice(sessions)
    doc = json.loads(base.read_text())
    folder = base.parent
    files = []
    sets = []
    if kind == "scene" and not (folder / str(doc.get("scene", ""))).is_file():
        kind = "session"
    if kind == "session":
        text, sets = mutate_json(rng, base.read_text())
    elif kind == "scene":
        scene = folder / doc["scene"]
        mutated = folder / f"fuzz_{index}.xml"
        mutated.write_bytes(mutate_xml(rng, scene.read_text()).encode("utf-8", "surrogateescape"))
        files.append(mutated)
        doc["scene"] = mutated.name
        text = json.dumps(doc)
    else:
        csvs = sorted((work / "scenes").glob("*_trajectory.csv"))
        source = rng.choice(csvs)
        mutated = folder / f"fuzz_{index}.csv"
        mutated.write_bytes(mutate_csv(rng, source.read_text()).encode("utf-8", "surrogateescape"))
        files.append(mutated)
        if rng.random() < 0.5:
            doc["device"] = {"type": rng.choice(["scripted", "hand"]), "trajectory": mutated.name}
        else:
            doc["device"] = {"type": "replay", "replay": mutated.name}
        text = json.dumps(doc)
    session = folder / f"fuzz_{index}.json"
    session.write_bytes(text.encode("utf-8", "surrogateescape"))
    files.append(session)
    return Case(index, kind, base.name, files, sets, session)


def call(mrh, args, cwd, timeout):
    start = time.monotonic()
    try:
        p = subprocess.run([mrh] + args, cwd=cwd, capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, b"", b"", time.monotonic() - start
    return p.returncode, p.stdout, p.stderr, time.monotonic() - start


def names_a_file(message, case, work):
    """True if the error starts with one of the case's files (as given or as resolved)."""
    candidates = set()
    for f in case.files + [case.session]:
        candidates.update({str(f), os.path.relpath(f, work), f.name})
    for f in (work / "scenes").iterdir():
        candidates.update({str(f), os.path.relpath(f, work)})
    for f in (work / "fixtures").iterdir():
        candidates.update({str(f), os.path.relpath(f, work)})
    head = re.match(r"^mrh: error: (.+?)(:\d+)*: ", message)
    return head is not None and head.group(1) in candidates


def check_call(what, code, out, err, elapsed, case, work, timeout):
    """Returns a list of problems of one call."""
    if code is None:
        return [f"{what}: hang (no exit within {timeout} s)"]
    if code < 0:
        return [f"{what}: killed by signal {-code}"]
    err_lines = err.decode(errors="replace").splitlines()
    out_lines = out.decode(errors="replace").splitlines()
    if code == 1 and what == "run" and len(err_lines) == 1 and \
            " the simulation diverged at t = " in err_lines[0]:
        if not names_a_file(err_lines[0], case, work):
            return [f"{what}: divergence does not name a file of the case: {err_lines[0]}"]
        return []
    if code not in (0, 2):
        return [f"{what}: exit code {code}: {err.decode(errors='replace')[:300]}"]
    problems = []
    if code == 2:
        if len(err_lines) != 1:
            problems.append(f"{what}: exit 2 with {len(err_lines)} stderr lines, expected 1")
        if not err_lines or not names_a_file(err_lines[0], case, work):
            problems.append(f"{what}: error does not start with a file of the case: "
                            f"{err_lines[:1]}")
        if out_lines:
            problems.append(f"{what}: exit 2 printed on stdout: {out_lines[:2]}")
        return problems
    stray = [l for l in err_lines if not l.startswith("mrh: warning: ")]
    stray += [l for l in out_lines if not re.match(r"^(ok|report|summary): ", l)]
    if stray:
        problems.append(f"{what}: output that is not mrh's own: {stray[:3]}")
    return problems


def run_case(case, mrh, work, timeout):
    sets = [a for s in case.sets for a in ("--set", s)] + ["--set", f"duration={RUN_DURATION}"]
    rel = os.path.relpath(case.session, work)
    out_dir = work / "out" / f"case_{case.index}"
    v = call(mrh, ["validate", rel] + sets, work, timeout)
    problems = check_call("validate", *v, case, work, timeout)
    r = call(mrh, ["run", rel, "--quiet", "--out", str(out_dir)] + sets, work, timeout)
    problems += check_call("run", *r, case, work, timeout)
    if v[0] in (0, 2) and r[0] in (0, 2) and v[0] != r[0]:
        problems.append(f"validate exit {v[0]} but run exit {r[0]}: "
                        f"{(v[2] + r[2]).decode(errors='replace')[:300]}")
    if r[0] == 0:
        try:
            ticks = json.loads((out_dir / "summary.json").read_text()).get("ticks", 0)
        except (OSError, ValueError) as e:
            ticks, problems = 0, problems + [f"run: exit 0 without a readable summary.json ({e})"]
        if not ticks:
            problems.append("run: exit 0 but no tick ran (silent no-op)")
    shutil.rmtree(out_dir, ignore_errors=True)
    return case, problems, max(v[3], r[3]), v[0], r[0]


def main():
    here = Path(__file__).resolve()
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mrh", required=True, help="path of the mrh binary")
    parser.add_argument("--root", default=str(here.parents[2]), help="repository root")
    parser.add_argument("--cases", type=int, default=300)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--timeout", type=float, default=30.0, help="s per mrh call")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--keep", default="", help="folder for the files of failing cases")
    a = parser.parse_args()
    mrh = str(Path(a.mrh).resolve())
    root = Path(a.root)
    rng = random.Random(a.seed)
    with tempfile.TemporaryDirectory(prefix="mrh_fuzz_") as tmp:
        work = Path(tmp)
        shutil.copytree(root / "scenes", work / "scenes")
        shutil.copytree(root / "tests" / "apps" / "fixtures", work / "fixtures")
        cases = [make_case(rng, i, root, work) for i in range(a.cases)]
        failures, codes, slowest = [], {}, 0.0
        with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
            futures = [pool.submit(run_case, c, mrh, work, a.timeout) for c in cases]
            for f in concurrent.futures.as_completed(futures):
                case, problems, elapsed, vcode, rcode = f.result()
                slowest = max(slowest, elapsed)
                codes[(vcode, rcode)] = codes.get((vcode, rcode), 0) + 1
                if problems:
                    failures.append((case, problems))
        for case, problems in sorted(failures, key=lambda x: x[0].index):
            print(f"FAIL case {case.index} ({case.kind} of {case.source}, sets {case.sets}):")
            for p in problems:
                print(f"  {p}")
            if a.keep:
                keep = Path(a.keep) / f"case_{case.index}"
                keep.mkdir(parents=True, exist_ok=True)
                for f in case.files:
                    shutil.copy(f, keep / f.name)
                (keep / "sets.txt").write_text("\n".join(case.sets) + "\n")
        summary = ", ".join(f"validate {v}/run {r}: {n}" for (v, r), n in sorted(
            codes.items(), key=lambda x: str(x[0])))
        print(f"fuzz: {a.cases} cases (seed {a.seed}), {len(failures)} failing; exit codes "
              f"{summary}; slowest call {slowest:.1f} s")
        return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
