#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Coulomb's answer for a 10 cm box pushed off centre by a frictionless edge (docs/theory.md).

The box (0.5 kg, half size a = 0.05 m, its centre h = 0.05 m above the floor) rests on its four
bottom corners, floor friction mu = 0.5 (isotropic, the elliptic cone). The pointer's inner edge,
a vertical line at world y = 0.01 m at the box's centre height, moves along +x at 0.1 m/s and
touches the box's -x face from t = 1 s. Quasi-static: at every instant the push (along the face
normal, at the edge) balances the floor's friction; the corner loads balance the weight and the
pitch and roll moments of the friction, 5 cm below the push (least-norm split: the four corners'
diagonal mode carries nothing, as in MuJoCo's and the island's regularised contacts); each
corner's friction is -mu N_i along its slip. The twist's direction and the push's size solve the
balance (Newton), its speed keeps the edge on the face, and the box is integrated until the edge
leaves the face. Prints the box's pose every 0.2 s and the impulse it received.
Usage: scripts/box-turn-quasistatic.py
"""
import numpy as np

M, G, MU, A, H = 0.5, 9.81, 0.5, 0.05, 0.05
EDGE_Y, SPEED, DT = 0.01, 0.1, 1e-3
CORNERS = np.array([[sx * A, sy * A] for sx in (-1, 1) for sy in (-1, 1)])


def corner_loads(friction):
    """Least-norm corner loads for the floor friction (box frame) and a push at the centre height."""
    roll, pitch = H * friction[1], -H * friction[0]
    rows = np.vstack([np.ones(4), CORNERS[:, 1], -CORNERS[:, 0]])
    return np.linalg.pinv(rows) @ np.array([M * G, -roll, -pitch])


def residual(u, s):
    """Force and moment balance (box frame) for v = (1, vy), omega = w, push F at (-A, s)."""
    vy, w, push = u
    v = np.array([1.0, vy])
    friction = np.array([-MU * M * G, 0.0])
    for _ in range(40):  # the loads depend on the friction's moments, which depend on the loads
        loads = corner_loads(friction)
        total, moment = np.zeros(2), 0.0
        for (x, y), n in zip(CORNERS, loads):
            slip = v + w * np.array([-y, x])
            f = -MU * n * slip / np.linalg.norm(slip)
            total += f
            moment += x * f[1] - y * f[0]
        friction = total
    return np.array([total[0] + push, total[1], moment - s * push])


def solve(s, u):
    for _ in range(40):
        r = residual(u, s)
        jac = np.zeros((3, 3))
        for k in range(3):
            du = np.zeros(3)
            du[k] = 1e-7
            jac[:, k] = (residual(u + du, s) - r) / 1e-7
        step = np.linalg.solve(jac, r)
        u = u - step
        if np.abs(step).max() < 1e-11:
            break
    return u


def rotation(th):
    return np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])


def main():
    x, y, th = 0.0, 0.0, np.radians(-0.3)  # a first turn puts the edge on the face
    t, u, impulse = 1.0, np.array([0.0, -5.0, 2.4]), np.zeros(2)
    while True:
        edge = np.array([-0.16 + SPEED * t + 0.01, EDGE_Y])
        c = rotation(th).T @ (edge - np.array([x, y]))  # the edge in the box frame
        if c[1] > A:
            print(f"edge leaves the face at t {t:.3f} s: box ({x:.4f}, {y:.4f}) m, "
                  f"yaw {np.degrees(th):.2f} deg; impulse on the box ({impulse[0]:.3f}, "
                  f"{impulse[1]:.3f}) N*s")
            return
        u = solve(c[1], u)
        vy, w, push = u
        impulse += DT * push * np.array([np.cos(th), np.sin(th)])
        contact = np.array([1.0, vy]) + w * np.array([-c[1], c[0]])
        scale = SPEED * np.cos(th) / contact[0]  # the contact follows the edge along the normal
        vw = rotation(th) @ np.array([1.0, vy]) * scale
        x, y, th = x + DT * vw[0], y + DT * vw[1], th + DT * w * scale
        c = rotation(th).T @ (edge + np.array([SPEED * DT, 0.0]) - np.array([x, y]))
        x, y = np.array([x, y]) + (c[0] + A) * rotation(th)[:, 0]  # keep the edge on the face
        t += DT
        if round(t * 1000) % 200 == 0:
            print(f"t {t:.1f} s: box ({x:.4f}, {y:.4f}) m, yaw {np.degrees(th):6.2f} deg, "
                  f"push {push:.3f} N at {c[1] * 1000:.1f} mm along the face from its centre")


if __name__ == "__main__":
    main()
