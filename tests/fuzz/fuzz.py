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

from mutators import mutate_csv, mutate_json, mutate_xml

RUN_DURATION = "0.03"  # s: every run is short; validate gets the same value


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
