#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
# A scripted subject for `mrh psychophysics run` under Xvfb: while process PID lives, moves the
# mouse over the window and presses 1 or 2 (from ANSWERS, cycled) every PERIOD seconds, through
# the XTest extension (libXtst, python3 standard library only).
# Usage: psychophysics_keys.py PID ANSWERS PERIOD   e.g. psychophysics_keys.py 1234 1122 0.3
import ctypes
import ctypes.util
import os
import sys
import time

pid, answers, period = int(sys.argv[1]), sys.argv[2], float(sys.argv[3])
x11 = ctypes.cdll.LoadLibrary(ctypes.util.find_library("X11") or "libX11.so.6")
xtst = ctypes.cdll.LoadLibrary(ctypes.util.find_library("Xtst") or "libXtst.so.6")
x11.XOpenDisplay.restype = ctypes.c_void_p
x11.XKeysymToKeycode.argtypes = [ctypes.c_void_p, ctypes.c_ulong]
x11.XFlush.argtypes = [ctypes.c_void_p]
xtst.XTestFakeKeyEvent.argtypes = [ctypes.c_void_p, ctypes.c_uint, ctypes.c_int, ctypes.c_ulong]
xtst.XTestFakeMotionEvent.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int, ctypes.c_int,
                                      ctypes.c_ulong]
display = x11.XOpenDisplay(None)
if not display:
    sys.exit("psychophysics_keys.py: cannot open the X display")


def alive():
    try:
        os.kill(pid, 0)
    except OSError:
        return False
    return True


# Keysyms of '1' and '2' are their ASCII codes.
codes = {a: x11.XKeysymToKeycode(display, ord(a)) for a in set(answers)}
i = 0
while alive():
    # With no window manager the keyboard focus follows the pointer: keep it over the window
    # (at the screen's top left), and wiggle it so that the mouse path runs too.
    xtst.XTestFakeMotionEvent(display, -1, 300 + 40 * (i % 3), 250, 0)
    code = codes[answers[i % len(answers)]]
    xtst.XTestFakeKeyEvent(display, code, 1, 0)
    xtst.XTestFakeKeyEvent(display, code, 0, 0)
    x11.XFlush(display)
    i += 1
    time.sleep(period)
