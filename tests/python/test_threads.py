# SPDX-License-Identifier: Apache-2.0
# run() releases the GIL while the engine works, and Ctrl-C (SIGINT) stops it cleanly.
import os
import signal
import threading
import time

import pytest

import mrhaptics
from conftest import read_csv

SESSION = "scenes/t4_1_impulse.json"


def test_another_thread_runs_while_run_works(root):
    # single-rate steps MuJoCo every tick: 30 s of it take a good fraction of a second.
    session = mrhaptics.load_session(root / SESSION, {"method": "single-rate", "duration": 30.0})
    stamps = []
    done = threading.Event()

    def count():
        while not done.is_set():
            stamps.append(time.perf_counter())
            time.sleep(0.0005)

    thread = threading.Thread(target=count)
    thread.start()
    time.sleep(0.01)
    begin = time.perf_counter()
    mrhaptics.run(session)
    end = time.perf_counter()
    done.set()
    thread.join()
    # Holding the GIL through run() would leave no stamp strictly inside it.
    middle = [s for s in stamps if begin + 0.25 * (end - begin) < s < end - 0.25 * (end - begin)]
    assert end - begin > 0.05, "the run was too short to tell"
    assert len(middle) >= 10, f"{len(middle)} stamps in the middle half of a {end - begin:.3f} s run"


def interrupt_after(seconds):
    timer = threading.Timer(seconds, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    return timer


@pytest.mark.parametrize("mode", ["lockstep", "realtime"])
def test_ctrl_c_stops_the_run_and_closes_its_files(root, tmp_path, mode):
    # 600 s of simulated (lockstep) or wall (realtime) time: only the interrupt ends it soon.
    # single-rate steps MuJoCo every tick, so even in lockstep the run lasts several seconds (the
    # impulse method finished 600 s in under 0.3 s on an idle machine, before the interrupt).
    session = mrhaptics.load_session(root / SESSION, {"duration": 600.0, "method": "single-rate"})
    timer = interrupt_after(0.3)
    begin = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        mrhaptics.run(session, mode=mode, out=tmp_path)
    elapsed = time.perf_counter() - begin
    timer.join()
    assert elapsed < 60.0
    summary = (tmp_path / "summary.json").read_text()
    ticks = read_csv(tmp_path / "ticks.csv")
    assert 0 < len(ticks["t"]) < 600_000
    assert f'"ticks": {len(ticks["t"])},' in summary
    # The interpreter is fine afterwards: the next run completes.
    assert mrhaptics.run(mrhaptics.load_session(root / SESSION, {"duration": 0.05})).summary[
        "ticks"] == 50
