#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Writes the thesis' demo D1 (thesis §4.6.4): scenes/d1.xml, 80 free objects of four
shapes (boxes, spheres, capsules, convex meshes) of different sizes and masses resting on a
table, and scenes/d1.json, the session that sweeps a simulated hand through them with the
proposed method (local-dynamics) in real time.

Usage: PYTHONPATH=build/deps scripts/make-d1-scene.py [--out-dir scenes] [--seed 36]

Deterministic: the same seed writes the same files. Objects stand on a 10 x 8 grid (9 cm pitch,
so neighbours are at least 2 cm apart), each at its resting height (10 um into the table), with a
small seeded jitter of position and yaw. With the MuJoCo Python bindings (`make deps`), the
script lets the scene settle for 1 s untouched and writes that state as the keyframe "settled"
(the session starts from it), then simulates 2 s from it and fails if any object moves more than
1 mm or is ever faster than 1 cm/s."""
import argparse
import json
import math
import random
import sys
from pathlib import Path

COLS, ROWS = 10, 8
PITCH = 0.09                  # m between grid cells
JITTER = 0.004                # m, uniform +- on x and y
TABLE_TOP = 0.75              # m, height of the table's top surface
TABLE_HALF = (0.60, 0.50)     # m, half extents of the top (the grid spans +-0.41 x +-0.32 m)
TABLE_THICK = 0.02            # m, half thickness of the top
PHYSICS_DT = 0.01             # s
POINTER_RADIUS = 0.02         # m
DENSITIES = (500.0, 1000.0, 2700.0)  # kg/m^3: wood, plastic, aluminium
MASS_RANGE = (0.03, 0.6)      # kg, masses are clamped to this
RIM = (0.01, 0.015)           # m, half thickness and height of the table's raised edge
# Objects start this far into the table: MuJoCo may miss a contact at exactly zero distance
# (dist < margin), and the object then falls freely for a step (1 mm, 0.1 m/s at 10 ms).
OVERLAP = 1e-5                # m
SHAPES = ("box", "sphere", "capsule", "mesh")
COLORS = {"box": "0.80 0.30 0.20 1", "sphere": "0.20 0.70 0.30 1",
          "capsule": "0.20 0.40 0.80 1", "mesh": "0.85 0.65 0.15 1"}


def fmt(x):
    return f"{x:.5f}".rstrip("0").rstrip(".") if x != 0 else "0"


def size(rng, lo, hi):
    """A dimension drawn from [lo, hi], rounded as the XML writes it."""
    return round(rng.uniform(lo, hi), 5)


def vec(*xs):
    return " ".join(fmt(x) for x in xs)


def hex_prism(rng):
    """Hexagonal prism standing on a face: vertices, half height, volume."""
    r, h = size(rng, 0.018, 0.03), size(rng, 0.012, 0.03)
    ring = [(r * math.cos(k * math.pi / 3), r * math.sin(k * math.pi / 3)) for k in range(6)]
    verts = [(x, y, z) for z in (-h, h) for x, y in ring]
    return verts, h, 1.5 * math.sqrt(3) * r * r * 2 * h


def frustum(rng):
    """Square frustum, top half as wide as the base: vertices, half height, volume."""
    a, h = size(rng, 0.02, 0.03), size(rng, 0.015, 0.03)
    b = 0.5 * a
    verts = [(sx * a, sy * a, -h) for sx in (-1, 1) for sy in (-1, 1)]
    verts += [(sx * b, sy * b, h) for sx in (-1, 1) for sy in (-1, 1)]
    s1, s2 = (2 * a) ** 2, (2 * b) ** 2
    return verts, h, 2 * h / 3 * (s1 + s2 + math.sqrt(s1 * s2))


def roof(rng):
    """Triangular prism lying on a rectangular face (ridge along y): vertices, half height,
    volume."""
    a, b, h = size(rng, 0.02, 0.03), size(rng, 0.015, 0.03), size(rng, 0.012, 0.025)
    verts = [(x, sy * b, -h) for x in (-a, a) for sy in (-1, 1)]
    verts += [(0.0, sy * b, h) for sy in (-1, 1)]
    return verts, h, a * 2 * h * 2 * b


MESHES = (hex_prism, frustum, roof)


def make_object(i, shape, rng):
    """(asset XML or "", body XML, resting half height) of object i."""
    x = (i % COLS - (COLS - 1) / 2) * PITCH + rng.uniform(-JITTER, JITTER)
    y = (i // COLS - (ROWS - 1) / 2) * PITCH + rng.uniform(-JITTER, JITTER)
    yaw = rng.uniform(-math.pi, math.pi)
    density = rng.choice(DENSITIES)
    name = f"{shape}{i:02d}"
    asset = ""
    if shape == "box":
        hx, hy, hz = (size(rng, 0.015, 0.03) for _ in range(3))
        rest, volume = hz, 8 * hx * hy * hz
        geom = f'type="box" size="{vec(hx, hy, hz)}"'
    elif shape == "sphere":
        r = size(rng, 0.015, 0.03)
        rest, volume = r, 4 / 3 * math.pi * r ** 3
        geom = f'type="sphere" size="{fmt(r)}"'
    elif shape == "capsule":  # lying on its side
        r, half = size(rng, 0.012, 0.02), size(rng, 0.012, 0.025)
        rest, volume = r, math.pi * r * r * 2 * half + 4 / 3 * math.pi * r ** 3
        geom = f'type="capsule" size="{vec(r, half)}" euler="0 90 0"'
    else:
        verts, rest, volume = MESHES[i % len(MESHES)](rng)
        asset = f'    <mesh name="{name}" vertex="{"  ".join(vec(*v) for v in verts)}"/>\n'
        geom = f'type="mesh" mesh="{name}"'
    mass = min(max(density * volume, MASS_RANGE[0]), MASS_RANGE[1])
    quat = vec(math.cos(yaw / 2), 0, 0, math.sin(yaw / 2))
    body = (f'    <body name="{name}" pos="{vec(x, y, TABLE_TOP + rest - OVERLAP)}" quat="{quat}">\n'
            f'      <freejoint/>\n'
            f'      <geom name="{name}" {geom} mass="{fmt(mass)}" rgba="{COLORS[shape]}"/>\n'
            f'    </body>\n')
    return asset, body


def scene_xml(seed):
    rng = random.Random(seed)
    # Twenty of each shape, shuffled over the grid.
    shapes = [SHAPES[k % len(SHAPES)] for k in range(COLS * ROWS)]
    rng.shuffle(shapes)
    assets, bodies = "", ""
    for i, shape in enumerate(shapes):
        a, b = make_object(i, shape, rng)
        assets += a
        bodies += b
    tx, ty = TABLE_HALF
    legs = "".join(
        f'    <geom name="leg{k}" type="box" size="0.03 0.03 {fmt((TABLE_TOP - 2 * TABLE_THICK) / 2)}"'
        f' pos="{vec(sx * (tx - 0.05), sy * (ty - 0.05), (TABLE_TOP - 2 * TABLE_THICK) / 2)}"'
        f' rgba="0.45 0.3 0.2 1"/>\n'
        for k, (sx, sy) in enumerate([(-1, -1), (1, -1), (-1, 1), (1, 1)]))
    rt, rh = RIM
    rim = "".join(
        f'    <geom name="rim{k}" type="box" size="{vec(*half)}" pos="{vec(*pos, TABLE_TOP + rh / 2)}"'
        f' rgba="0.5 0.35 0.25 1"/>\n'
        for k, (half, pos) in enumerate([
            ((tx, rt, rh / 2), (0, -(ty - rt))), ((tx, rt, rh / 2), (0, ty - rt)),
            ((rt, ty - 2 * rt, rh / 2), (-(tx - rt), 0)), ((rt, ty - 2 * rt, rh / 2), (tx - rt, 0))]))
    return f"""<!-- SPDX-License-Identifier: Apache-2.0 -->
<!-- Demo D1 (thesis §4.6.4): 80 free objects - boxes, spheres, capsules lying on their
     sides and convex meshes (hexagonal prisms, square frustums, roof prisms) - of different sizes
     and masses (densities 500, 1000, 2700 kg/m^3) resting on a table with a raised edge, for a simulated hand to
     feel by motion, shape and weight. Written by scripts/make-d1-scene.py --seed {seed}; edit
     the script, not this file. -->
<mujoco model="d1">
  <!-- Elliptic cones: Coulomb's isotropic friction (a pyramidal cone makes a straight push an
       unstable equilibrium, see t4_push_wall.xml). Sliding friction only (condim 3): the local
       simulation has no rolling or torsional friction, so with condim 6 a touched ball would roll
       freely there and be braked by MuJoCo once released. A pushed ball rolls on until it hits
       something: the table has a raised edge. -->
  <option timestep="{fmt(PHYSICS_DT)}" gravity="0 0 -9.81" cone="elliptic"/>
  <default>
    <geom condim="3" friction="0.5 0.005 0.0001"/>
  </default>
  <asset>
{assets}  </asset>
  <worldbody>
    <light pos="0 -1.5 2.5" dir="0 0.5 -1"/>
    <geom name="floor" type="plane" size="3 3 0.1" rgba="0.85 0.85 0.85 1"/>
    <geom name="table" type="box" size="{vec(tx, ty, TABLE_THICK)}" pos="{vec(0, 0, TABLE_TOP - TABLE_THICK)}"
          rgba="0.6 0.45 0.3 1"/>
{legs}{rim}{bodies}    <body name="pointer" mocap="true" pos="{vec(*HAND_START)}">
      <geom name="pointer" type="sphere" size="{fmt(POINTER_RADIUS)}" contype="0" conaffinity="0"
            rgba="0.95 0.8 0.1 0.9"/>
    </body>
  </worldbody>
</mujoco>
"""


# The hand's target path (t, x, y, z in the world): down beside the grid, along the row at
# y = +0.045 pushing its first objects into the next ones, up, then down beside the grid again
# and along the gap between the columns at x = 0.09 and 0.27 brushing both sides, and up. The
# pointer centre runs 3 cm above the table: below the centre of the tallest objects, 1 cm clear
# of the top.
LOW, HIGH = TABLE_TOP + 0.03, TABLE_TOP + 0.2
HAND_PATH = [
    (0.0, -0.52, 0.045, HIGH),
    (1.0, -0.52, 0.045, LOW),
    (4.0, -0.05, 0.045, LOW),
    (4.8, -0.05, 0.045, HIGH),
    (6.0, 0.18, -0.42, HIGH),
    (7.0, 0.18, -0.42, LOW),
    (9.5, 0.18, 0.25, LOW),
    (10.0, 0.18, 0.25, HIGH),
]
HAND_START = HAND_PATH[0][1:]


def session_json():
    return {
        "scene": "d1.xml",
        "method": "local-dynamics",
        "mode": "realtime",
        "physics_dt": PHYSICS_DT,
        "haptic_dt": 0.001,
        "duration": 10.0,
        "keyframe": "settled",
        "pointer": {"body": "pointer", "radius": POINTER_RADIUS},
        "rendering": {"stiffness": 1000.0, "damping": 2.0},
        "device": {
            "type": "hand",
            "keyframes": [[t, x, y, z, 1, 0, 0, 0] for t, x, y, z in HAND_PATH],
            "hand": {"mass": 0.5, "stiffness": 300.0, "damping": 20.0},
            "limits": {"max_force": 20.0},
        },
    }


def load(xml):
    try:
        import mujoco
    except ImportError as e:
        sys.exit(f"make-d1-scene.py needs the MuJoCo bindings (PYTHONPATH=build/deps): {e}")
    m = mujoco.MjModel.from_xml_string(xml)
    return mujoco, m, mujoco.MjData(m)


def settled_keyframe(xml):
    """The keyframe "settled": every object where MuJoCo's soft contacts hold it after 1 s
    untouched (they sink ~0.3 mm into the table at first), at rest."""
    mujoco, m, d = load(xml)
    for _ in range(round(1.0 / m.opt.timestep)):
        mujoco.mj_step(m, d)
    rows = [" ".join(f"{q:.7f}" for q in d.qpos[a:a + 7])
            for a in range(0, m.nq, 7)]
    qpos = "\n                          ".join(rows)
    return f'  <keyframe>\n    <key name="settled" qpos="{qpos}"/>\n  </keyframe>\n'


def settle_check(xml):
    """Simulates the scene untouched for 2 s from its keyframe; returns an error line or ""."""
    mujoco, m, d = load(xml)
    mujoco.mj_resetDataKeyframe(m, d, 0)
    mujoco.mj_forward(m, d)
    deepest = min((d.contact[c].dist for c in range(d.ncon)), default=0.0)
    if deepest < -1e-3:
        return f"d1.xml: a contact starts {-deepest * 1e3:.2f} mm deep; expected objects at rest"
    import numpy as np
    free = [b for b in range(m.nbody) if m.body_jntnum[b] == 1 and
            m.jnt_type[m.body_jntadr[b]] == mujoco.mjtJoint.mjJNT_FREE]
    x0 = d.xipos[free].copy()
    dofs = [m.jnt_dofadr[m.body_jntadr[b]] for b in free]
    moved = speed = 0.0
    for _ in range(round(2.0 / m.opt.timestep)):
        mujoco.mj_step(m, d)
        moved = max(moved, np.linalg.norm(d.xipos[free] - x0, axis=1).max())
        speed = max(speed, max(np.linalg.norm(d.qvel[a:a + 3]) for a in dofs))
    print(f"settle: {len(free)} objects, {d.ncon} contacts; over 2 s from the keyframe, largest "
          f"displacement {moved * 1e3:.4f} mm, largest speed {speed * 1e3:.4f} mm/s")
    if moved > 1e-3 or speed > 1e-2:
        return f"d1.xml: objects do not rest (moved {moved * 1e3:.3f} mm, {speed:.4f} m/s)"
    return ""


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out-dir", default=str(Path(__file__).resolve().parent.parent / "scenes"))
    p.add_argument("--seed", type=int, default=36)
    a = p.parse_args()
    out = Path(a.out_dir)
    xml = scene_xml(a.seed)
    xml = xml.replace("</mujoco>\n", settled_keyframe(xml) + "</mujoco>\n")
    error = settle_check(xml)
    if error:
        print(error, file=sys.stderr)
        return 1
    (out / "d1.xml").write_text(xml)
    (out / "d1.json").write_text(json.dumps(session_json(), indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
