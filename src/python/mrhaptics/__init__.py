# SPDX-License-Identifier: Apache-2.0
"""mrhaptics: multi-rate haptic rendering of MuJoCo worlds, from Python.

Load a session file, change what you like, run it and read its records as numpy arrays::

    import mrhaptics
    session = mrhaptics.load_session("scenes/t4_1_impulse.json",
                                      {"rendering.stiffness": 1500, "duration": 0.5})
    result = mrhaptics.run(session)          # lockstep: the CLI's numbers, bit for bit
    result.ticks["fx"]                       # numpy float64, one value per haptic tick

or put the engine in your own servo loop with Engine (device.type "external").
See docs/python.md.
"""

import json as _json
import os as _os
from typing import Any, Mapping, Optional, Union

from ._mrhaptics import Engine, Result, Session, __version__, methods, run
from ._mrhaptics import _load_session

__all__ = ["Engine", "Result", "Session", "load_session", "methods", "run", "__version__"]


def _json_value(value: Any) -> str:
    # numpy scalars and arrays carry .tolist(); everything else is JSON as it is.
    if hasattr(value, "tolist"):
        value = value.tolist()
    return _json.dumps(value, allow_nan=False)


def load_session(path: Union[str, "_os.PathLike[str]"],
                 overrides: Optional[Mapping[str, Any]] = None) -> Session:
    """Reads, overrides and validates a session file, as `mrh run --set KEY=VALUE` does.

    overrides: dotted keys to values, e.g. {"rendering.stiffness": 1500, "method": "impulse",
    "device": {"type": "external"}}. Each value is encoded as JSON (a str stays a string), so
    {"rendering.stiffness": 1500} equals `--set rendering.stiffness=1500`.

    Raises ValueError with the CLI's one-line message (file, key, value, fix) for a missing or
    unreadable file, an unknown key, a wrong type or a bad value.
    """
    strings = []
    for key, value in (overrides or {}).items():
        if not isinstance(key, str):
            raise ValueError(f"load_session: override key {key!r} is not a str; expected a dotted "
                             "session key such as 'rendering.stiffness'")
        try:
            strings.append(f"{key}={_json_value(value)}")
        except (TypeError, ValueError) as error:
            raise ValueError(f"load_session: override {key} = {value!r} is not a JSON value "
                             f"(number, bool, str, list, dict or None): {error}") from None
    return _load_session(_os.fspath(path), strings)
