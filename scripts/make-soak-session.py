#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Writes the reliability soak's session: a simulated hand (mass 0.5 kg, 300 N/m, 20 N·s/m)
sweeps scenes/soak150.xml row by row at 0.28 m/s, 3 cm above the floor, lifting between rows,
back and forth, for as long as asked; each pass over the seven rows shifts its lanes by a few
millimetres so the hand meets the objects (by then scattered) differently.

Usage: scripts/make-soak-session.py [--duration 600] [--method local-dynamics]
                                    [--out scenes/soak150_600s.json]

The first 43 s are the keyframes of the original reproducer (40 s of it is scenes/soak150.json).
Deterministic: the same arguments write the same file."""
import argparse
import json

X_END = 0.7            # m, the sweep runs from -X_END to +X_END
Z_LOW, Z_LIFT = 0.03, 0.15
SWEEP_S, LIFT_S = 5.0, 0.5   # s: one row at 1.4 m / 5 s = 0.28 m/s; lift and lower
LANES = [-0.315 + 0.07 * k for k in range(7)]
SHIFT = 0.006          # m per pass


def keyframes(duration):
    k = [[0.0, -X_END, 0.0, 0.3], [1.0, -X_END, 0.0, Z_LOW]]
    t, x, y = 1.0, -X_END, 0.0
    lap = 0
    while t < duration + SWEEP_S:
        lanes = LANES if lap % 2 == 0 else LANES[::-1]
        for lane in lanes:
            lane = lane + SHIFT * (lap % 5)
            t += LIFT_S                              # to the lane (first lane: from the start)
            k.append([t, x, lane, Z_LOW])
            x = -x
            t += SWEEP_S
            k.append([t, x, lane, Z_LOW])
            t += LIFT_S
            k.append([t, x, lane, Z_LIFT])
        lap += 1
    return [[round(v, 6) for v in f] + [1, 0, 0, 0] for f in k]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--duration", type=float, default=600.0, help="seconds (default 600)")
    ap.add_argument("--method", default="local-dynamics")
    ap.add_argument("--out", default="scenes/soak150_600s.json")
    a = ap.parse_args()
    if not a.duration > 0:
        ap.error(f"--duration must be > 0 (got {a.duration})")
    session = {
        "scene": "soak150.xml",
        "method": a.method,
        "mode": "lockstep",
        "physics_dt": 0.02,
        "haptic_dt": 0.001,
        "duration": a.duration,
        "realtime_priority": False,
        "pointer": {"body": "pointer"},
        "rendering": {"stiffness": 1000.0, "damping": 2.0},
        "device": {
            "type": "hand",
            "keyframes": keyframes(a.duration),
            "hand": {"mass": 0.5, "stiffness": 300.0, "damping": 20.0},
            "limits": {"max_force": 20.0},
        },
    }
    text = json.dumps(session, indent=2)
    # One keyframe per line.
    rows = ",\n      ".join(json.dumps(f) for f in session["device"]["keyframes"])
    start = text.index('"keyframes": [') + len('"keyframes": [')
    end = text.index("]\n    ],", start) + len("]\n    ]")
    text = text[:start] + "\n      " + rows + "\n    ]" + text[end:]
    with open(a.out, "w") as f:
        f.write(text + "\n")
    print(f"{a.out}: {a.duration:g} s, {len(session['device']['keyframes'])} keyframes")


if __name__ == "__main__":
    main()
