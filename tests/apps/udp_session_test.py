#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""A `udp` session in real time against a test client: the device's counters reach summary.json.

Usage: udp_session_test.py MRH SESSION OUT_DIR

The client (the packet format of docs/devices.md) waits until mrh answers, then sends a known
number of well-formed poses and of malformed packets, and falls silent for the rest of the run
so that the pose timeout fires. summary.json's "device" block must agree with what it sent.
"""
import json
import math
import os
import socket
import struct
import subprocess
import sys
import time

POSE = struct.Struct("<4sIQd3d4dII")  # 88 bytes
WRENCH = struct.Struct("<4sIQ6dII")  # 72 bytes
DURATION = 1.5  # s of the run
SEND_FOR = 0.5  # s of poses after the first answer; then silence
TIMEOUT = 0.05  # s, device.timeout
MALFORMED = 7  # packets with a wrong magic


def free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def pose(seq, t):
    return POSE.pack(b"MRHP", 1, seq, t, 0.0, 0.0, 0.12, 1.0, 0.0, 0.0, 0.0, 0, 0)


def fail(message, mrh_output=""):
    print(f"FAIL: {message}", file=sys.stderr)
    if mrh_output:
        print(f"--- mrh output:\n{mrh_output}", file=sys.stderr)
    sys.exit(1)


def main():
    mrh, session, out = sys.argv[1:4]
    port = free_port()
    device = {"type": "udp", "bind": f"127.0.0.1:{port}", "timeout": TIMEOUT, "fade": 0.01}
    run = subprocess.Popen(
        [mrh, "run", session, "--mode", "realtime", "--duration", str(DURATION), "--quiet",
         "--out", out, "--set", "realtime_priority=false", "--set", f"device={json.dumps(device)}"],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sock.settimeout(0.01)
    server = ("127.0.0.1", port)
    seq = 0
    answers = 0
    # Until mrh has bound its socket, poses are lost: resend until the first wrench comes back.
    give_up = time.monotonic() + 30.0
    while answers == 0:
        if time.monotonic() > give_up or run.poll() is not None:
            run.kill()
            fail("no wrench from mrh within 30 s", run.communicate()[0])
        seq += 1
        sock.sendto(pose(seq, 0.0), server)
        try:
            data = sock.recv(128)
            answers += WRENCH.unpack(data)[0] == b"MRHW"
        except socket.timeout:
            pass
    sent_before = seq  # some of these arrived, at least the one answered
    sock.setblocking(False)
    start = time.monotonic()
    for i in range(MALFORMED):
        sock.sendto(b"XXXX" + pose(0, 0.0)[4:], server)
    while time.monotonic() - start < SEND_FOR:
        seq += 1
        sock.sendto(pose(seq, time.monotonic() - start), server)
        try:
            while True:
                answers += WRENCH.unpack(sock.recv(128))[0] == b"MRHW"
        except BlockingIOError:
            pass
        time.sleep(0.001)
    sent_after = seq - sent_before
    output = run.communicate(timeout=60)[0]
    if run.returncode != 0:
        fail(f"mrh exited {run.returncode}", output)

    with open(os.path.join(out, "summary.json"), encoding="utf-8") as f:
        counters = json.load(f)["device"]
    print(f"sent {sent_before} handshake + {sent_after} poses, {MALFORMED} malformed; "
          f"received {answers} wrenches; summary device = {counters}")
    received = counters["poses_received"]
    if not sent_after + 1 <= received <= sent_after + sent_before:
        fail(f"poses_received = {received}; expected {sent_after + 1}..{sent_after + sent_before}")
    if counters["packets_malformed"] != MALFORMED:
        fail(f"packets_malformed = {counters['packets_malformed']}; expected {MALFORMED}")
    # Silent for the last ~1 s of the run at 1 kHz: hundreds of ticks without a fresh pose.
    silent_ticks = (DURATION - SEND_FOR - TIMEOUT) * 1000.0
    if not 0.3 * silent_ticks <= counters["pose_timeouts"] <= DURATION * 1000.0:
        fail(f"pose_timeouts = {counters['pose_timeouts']}; expected about {silent_ticks:.0f}")
    if counters["wrenches_sent"] < answers:
        fail(f"wrenches_sent = {counters['wrenches_sent']} < {answers} received by the client")
    print("ok")


if __name__ == "__main__":
    main()
