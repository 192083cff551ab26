#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Two pointers on two UDP ports in one real-time `mrh run`: each client moves its own finger.

Usage: udp_pointers_session_test.py MRH SESSION OUT_DIR

SESSION is scenes/two_finger_grasp.json (0.2 kg box 0.1 m wide along y, centred at the origin,
fingertips r = 0.01 m, rendering.stiffness 800 N/m). Its `pointers` are replaced by two `udp`
devices on two free loopback ports. The thumb's client holds its finger 1 mm into the box's -y
face, the index's holds its finger in free space. Each client must get wrenches back on its own
port: the thumb's pushed out of the box (f_y < 0), the index's zero; and summary.json's
per-pointer device counters must show each port's poses.
"""
import json
import os
import socket
import struct
import subprocess
import sys
import time

POSE = struct.Struct("<4sIQd3d4dII")  # 88 bytes
WRENCH = struct.Struct("<4sIQ6dII")  # 72 bytes
DURATION = 1.5  # s of the run
# m: the thumb 1 mm into the -y face (face at -0.05, r = 0.01): 800 N/m × 1 mm = 0.8 N, less
# than the floor's static friction on the box (mu 1 × 0.2 kg × g = 1.96 N).
THUMB_Y = -0.059
INDEX_P = (0.0, 0.3, 0.3)  # m, far from everything
# Before its first pose a udp device reads the origin, inside the box: each device's origin is
# put 0.5 m above the scene (calibration.position) so that no finger starts inside the box.
LIFT = 0.5  # m


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def pose(seq, p):
    return POSE.pack(b"MRHP", 1, seq, 0.0, p[0], p[1], p[2], 1.0, 0.0, 0.0, 0.0, 0, 0)


def fail(message, mrh_output=""):
    print(f"FAIL: {message}", file=sys.stderr)
    if mrh_output:
        print(f"--- mrh output:\n{mrh_output}", file=sys.stderr)
    sys.exit(1)


def main():
    mrh, session, out = sys.argv[1:4]
    ports = [free_port(), free_port()]
    while ports[1] == ports[0]:
        ports[1] = free_port()
    pointers = [{"body": body, "radius": 0.01,
                 "device": {"type": "udp", "bind": f"127.0.0.1:{port}", "timeout": 10.0,
                            "fade": 0.0, "calibration": {"position": [0.0, 0.0, LIFT]}}}
                for body, port in zip(("thumb", "index"), ports)]
    run = subprocess.Popen(
        [mrh, "run", session, "--mode", "realtime", "--duration", str(DURATION), "--quiet",
         "--out", out, "--set", "realtime_priority=false", "--set",
         f"pointers={json.dumps(pointers)}"],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    socks = [socket.socket(socket.AF_INET, socket.SOCK_DGRAM) for _ in ports]
    for s in socks:
        s.setblocking(False)
    # Device frame: the world position less the calibration's lift.
    where = [(0.0, THUMB_Y, 0.03 - LIFT), (INDEX_P[0], INDEX_P[1], INDEX_P[2] - LIFT)]
    # Per client: wrenches received, the most negative f_y and the largest |f| among them (the
    # last wrench is zero: the stop commands zero).
    got = [0, 0]
    min_fy = [0.0, 0.0]
    max_f = [0.0, 0.0]
    sent = [0, 0]
    give_up = time.monotonic() + 30.0
    # Poses until mrh ends; a pose sent before mrh bound its port is lost, which is fine.
    while run.poll() is None:
        if time.monotonic() > give_up:
            run.kill()
            fail("mrh did not end within 30 s", run.communicate()[0])
        for i, s in enumerate(socks):
            sent[i] += 1
            s.sendto(pose(sent[i], where[i]), ("127.0.0.1", ports[i]))
            try:
                while True:
                    w = WRENCH.unpack(s.recv(128))
                    if w[0] == b"MRHW":
                        got[i] += 1
                        min_fy[i] = min(min_fy[i], w[4])
                        max_f[i] = max(max_f[i], (w[3] ** 2 + w[4] ** 2 + w[5] ** 2) ** 0.5)
            except BlockingIOError:
                pass
        time.sleep(0.001)
    output = run.communicate(timeout=60)[0]
    if run.returncode != 0:
        fail(f"mrh exited {run.returncode}", output)
    print(f"ports {ports}; wrenches {got}; min f_y {min_fy}; max |f| {max_f}")
    if 0 in got:
        fail(f"a client got no wrench back: {got}")
    # At most 0.8 N out of the face: the engage ramp brings it in over 0.5 s while the box creeps
    # away from the constant push (MuJoCo's soft contacts; 0.28 N at most, measured), so the
    # check is that the thumb touches (pushed along -y) and the index does not.
    if not min_fy[0] < -0.05:
        fail(f"thumb's most negative f_y = {min_fy[0]}; expected the box to push it out along -y")
    if max_f[1] != 0.0:
        fail(f"index's largest |f| = {max_f[1]}; expected zero in free space")
    with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
        summary = json.load(f)
    for i, p in enumerate(summary["pointers"]):
        received = p["device"]["poses_received"]
        if not 0 < received <= sent[i]:
            fail(f"pointers[{i}] poses_received = {received}; sent {sent[i]}")
    print("ok")


if __name__ == "__main__":
    main()
