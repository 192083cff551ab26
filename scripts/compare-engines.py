#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Runs every experiment with two `mrh` binaries (e.g. built on two MuJoCo versions) and compares
their summary.json files: each experiment's own checks and every number in it.

Usage: scripts/compare-engines.py OLD_MRH NEW_MRH OUT_DIR [--only NAME ...] [--labels A B]
       [--no-run]

Writes OUT_DIR/compare.csv (experiment, key, old, new, relative change) and OUT_DIR/compare.md
(per experiment: run status, checks, and the numbers that changed by more than 1e-9 relative).
Run it on an idle machine: some experiments report wall-clock timings."""
import argparse
import csv
import json
import math
import re
import subprocess
import sys
import time
from pathlib import Path


def experiments(mrh):
    out = subprocess.run([mrh, "experiment", "--list"], capture_output=True, text=True, check=True)
    return [line.split()[0] for line in out.stdout.splitlines() if line.strip()]


def run(mrh, name, out_dir):
    start = time.monotonic()
    proc = subprocess.run([mrh, "experiment", name, "--out", str(out_dir), "-q"],
                          capture_output=True, text=True)
    return proc.returncode, time.monotonic() - start, (proc.stderr or proc.stdout).strip()[-300:]


def leaves(value, prefix=""):
    """(key, value) for every number or boolean in a JSON document, keys joined with '.'."""
    if isinstance(value, dict):
        for k, v in value.items():
            yield from leaves(v, f"{prefix}.{k}" if prefix else k)
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from leaves(v, f"{prefix}[{i}]")
    elif isinstance(value, bool) or isinstance(value, (int, float)):
        yield prefix, value


def load(path):
    try:
        return dict(leaves(json.loads(path.read_text())))
    except (OSError, ValueError):
        return {}


# Keys of wall-clock figures (timings, occupancy, real-time ratios): they move with the machine's
# load, not with the engine's physics, and are kept out of the summary's "largest change".
TIMING = re.compile(r"(_ms|_us|_s_per|ms_|us_|occupancy|ratio_p|cpu|wall|cost|realtime|time_s|"
                    r"jitter|per_tick|per_step|seconds|\.ratio$)", re.IGNORECASE)
# Numbers below this in magnitude on both sides are roundoff (e.g. 1e-13 accelerance errors):
# their relative change says nothing and is kept out of the summary too.
ROUNDOFF = 1e-9


def relative(old, new):
    if isinstance(old, bool) or isinstance(new, bool):
        return None
    if old == new:
        return 0.0
    scale = max(abs(old), abs(new))
    return (new - old) / scale if scale > 0 and math.isfinite(scale) else math.inf


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("out", type=Path)
    parser.add_argument("--only", nargs="*", default=None, help="experiment names (default: all)")
    parser.add_argument("--labels", nargs=2, default=["old", "new"])
    parser.add_argument("--no-run", action="store_true",
                        help="compare the summaries already in OUT_DIR/old and OUT_DIR/new")
    args = parser.parse_args()
    names = args.only or experiments(args.new)
    rows, report, summary = [], [], []
    for name in names:
        status = {}
        for label, mrh in (("old", args.old), ("new", args.new)):
            if args.no_run:
                code, seconds, tail = 0, 0.0, ""
            else:
                code, seconds, tail = run(mrh, name, args.out / label / name)
            status[label] = (code, seconds, tail)
            print(f"{name:12s} {label}: exit {code}, {seconds:.1f} s", file=sys.stderr)
        old = load(args.out / "old" / name / "summary.json")
        new = load(args.out / "new" / name / "summary.json")
        report.append(f"## {name}\n")
        report.append(f"exit {status['old'][0]} ({status['old'][1]:.1f} s) → "
                      f"exit {status['new'][0]} ({status['new'][1]:.1f} s)\n")
        checks = sorted(k for k in set(old) | set(new) if k.startswith("checks."))
        if checks:
            report.append(f"| check | {args.labels[0]} | {args.labels[1]} |\n|---|---|---|")
            for k in checks:
                report.append(f"| {k[7:]} | {old.get(k, '—')} | {new.get(k, '—')} |")
            report.append("")
        passed = lambda d: (sum(1 for k in checks if d.get(k) is True), len(checks))
        changed = []
        for k in sorted(set(old) | set(new)):
            if k.startswith("checks."):
                continue
            o, n = old.get(k), new.get(k)
            r = relative(o, n) if o is not None and n is not None else None
            rows.append([name, k, o, n, r])
            if o is None or n is None or (r is not None and abs(r) > 1e-9):
                changed.append((k, o, n, r))
        numbers = [k for k in set(old) | set(new) if not k.startswith("checks.")]
        physics = [c for c in changed if not TIMING.search(c[0]) and c[3] is not None
                   and max(abs(c[1]), abs(c[2])) > ROUNDOFF]
        worst = max(physics, key=lambda c: abs(c[3]), default=None)
        summary.append(
            f"| {name} | {status['old'][0]} / {status['new'][0]} | "
            f"{'%d of %d' % passed(old)} / {'%d of %d' % passed(new)} | "
            f"{len(numbers) - len(changed)} of {len(numbers)} | "
            + (f"{worst[0]}: {worst[1]:.6g} → {worst[2]:.6g} ({100 * worst[3]:+.1f} %)"
               if worst else "none") + " |")
        if changed:
            report.append(f"| number | {args.labels[0]} | {args.labels[1]} | change |\n"
                          "|---|---|---|---|")
            for k, o, n, r in changed:
                fmt = lambda v: "—" if v is None else (f"{v:.6g}" if isinstance(v, float) else v)
                rc = "—" if r is None else f"{100 * r:+.2f} %"
                report.append(f"| {k} | {fmt(o)} | {fmt(n)} | {rc} |")
            report.append("")
        else:
            report.append("every number identical\n")
    args.out.mkdir(parents=True, exist_ok=True)
    with open(args.out / "compare.csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["experiment", "key", "old", "new", "relative_change"])
        writer.writerows(rows)
    head = [f"# {args.labels[0]} → {args.labels[1]}\n",
            f"| experiment | exit | checks passed | numbers identical | largest change of a "
            f"non-timing number |\n|---|---|---|---|---|"] + summary + [""]
    (args.out / "compare.md").write_text("\n".join(head + report) + "\n")
    print(args.out / "compare.md")


if __name__ == "__main__":
    main()
