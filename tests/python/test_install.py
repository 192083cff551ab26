# SPDX-License-Identifier: Apache-2.0
# `make install`'s Python part (cmake --install --component python), staged with DESTDIR: the
# installed package imports and runs without the build tree on PYTHONPATH.
import os
import pathlib
import subprocess
import sys

import pytest


def test_installed_package_runs_without_the_build_tree(root, tmp_path):
    build = os.environ.get("MRH_BUILD_DIR")
    cmake = os.environ.get("CMAKE_COMMAND")
    site = os.environ.get("MRH_PYTHON_INSTALL_DIR")
    if not (build and cmake and site):
        pytest.fail("run through ctest, which sets MRH_BUILD_DIR, CMAKE_COMMAND and "
                    "MRH_PYTHON_INSTALL_DIR")
    env = dict(os.environ, DESTDIR=str(tmp_path))
    subprocess.run([cmake, "--install", build, "--component", "python"], env=env, check=True,
                   capture_output=True)
    staged = tmp_path / pathlib.Path(site).relative_to("/")
    assert (staged / "mrhaptics" / "__init__.pyi").is_file()
    # Only the staged package and the pinned numpy: nothing of build/python.
    deps = [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep)
            if p and pathlib.Path(p).resolve() != (pathlib.Path(build) / "python").resolve()]
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(staged), *deps]))
    script = ("import mrhaptics, sys; "
              "s = mrhaptics.load_session('scenes/t4_1_impulse.json', {'duration': 0.05}); "
              "print(mrhaptics.__file__); print(mrhaptics.run(s).summary['ticks'])")
    done = subprocess.run([sys.executable, "-c", script], cwd=root, env=env, capture_output=True,
                          text=True, check=True)
    where, ticks = done.stdout.split()
    assert pathlib.Path(where).is_relative_to(staged)
    assert ticks == "50"
