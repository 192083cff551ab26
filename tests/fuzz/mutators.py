# SPDX-License-Identifier: Apache-2.0
"""The fuzzer's mutations of mrh's inputs: session JSON (wrong types, extreme and non-finite
numbers, duplicate keys, deep nesting, bad --set values), MJCF scenes, CSV trajectories and raw
bytes (truncation, binary junk). Deterministic given the random.Random passed in.
"""
import json
import random
import re

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
