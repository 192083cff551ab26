# SPDX-License-Identifier: Apache-2.0
# Shared fixtures of the Python tests: the source tree, the CLI to compare against, CSV reading.
# ctest sets MRH_SOURCE_DIR, MRH_CLI and PYTHONPATH (tests/python/CMakeLists.txt).
import csv
import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(os.environ.get("MRH_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))


@pytest.fixture(scope="session")
def root() -> pathlib.Path:
    return ROOT


@pytest.fixture(scope="session")
def mrh_cli() -> pathlib.Path:
    cli = pathlib.Path(os.environ.get("MRH_CLI", ROOT / "build" / "bin" / "mrh"))
    if not cli.is_file():
        pytest.fail(f"no mrh CLI at {cli}; build it (cmake --build build --target mrh)")
    return cli


def run_cli(cli, *args, check=True):
    """Runs `mrh ARGS` in the source tree; returns the CompletedProcess (text)."""
    done = subprocess.run([str(cli), *map(str, args)], cwd=ROOT, capture_output=True, text=True,
                          timeout=300)
    if check and done.returncode != 0:
        pytest.fail(f"mrh {' '.join(map(str, args))} exited {done.returncode}: {done.stderr}")
    return done


def read_csv(path):
    """A CSV file of `mrh run` as {column: numpy array}: float64 parsed by Python's correctly
    rounded float(), the body column as str."""
    with open(path, newline="") as file:
        rows = list(csv.reader(file))
    header, rows = rows[0], rows[1:]
    columns = {}
    for i, name in enumerate(header):
        values = [row[i] for row in rows]
        columns[name] = np.array(values) if name == "body" else np.array(
            [float(v) for v in values], dtype=np.float64)
    return columns


def assert_columns_equal(got, want, columns=None):
    """Every column of `want` (or the named ones) equal in `got`, floats bit for bit."""
    if columns is None:
        assert list(got) == list(want), "the columns differ from the CLI's file header"
    for name in columns or want:
        a, b = got[name], want[name]
        assert len(a) == len(b), f"{name}: {len(a)} values, the CLI's file has {len(b)}"
        if name == "body":
            assert a.dtype.kind == "U" and list(a) == list(b), name
            continue
        if a.dtype.kind == "i":
            assert np.array_equal(a.astype(np.float64), b), name
            continue
        assert a.dtype == np.float64, f"{name}: {a.dtype}"
        same = a.view(np.uint64) == b.view(np.uint64)
        if not same.all():
            first = int(np.argmin(same))
            pytest.fail(f"{name}[{first}] = {a[first]!r}, the CLI's file has {b[first]!r}")
