# SPDX-License-Identifier: Apache-2.0
# Keeps docs/python.md honest: its example runs, and prints what the page says it prints.
import os
import re
import subprocess
import sys


def blocks(markdown, language):
    return re.findall(rf"```{language}\n(.*?)```", markdown, flags=re.S)


def test_the_example_prints_what_the_page_shows(root, tmp_path):
    page = (root / "docs" / "python.md").read_text()
    code, shown = blocks(page, "python"), blocks(page, "text")
    assert code and len(code) == len(shown), "each python block is followed by its output"
    env = dict(os.environ, MPLBACKEND="Agg", MRH_PLOT_DIR=str(tmp_path))
    for i, (script, output) in enumerate(zip(code, shown)):
        done = subprocess.run([sys.executable, "-c", script], cwd=root, env=env,
                              capture_output=True, text=True, timeout=240)
        assert done.returncode == 0, f"block {i}: {done.stderr}"
        # The plot line depends on whether matplotlib is installed; the numbers do not.
        printed = [l for l in done.stdout.splitlines() if not l.startswith("plot:")]
        wanted = [l for l in output.splitlines() if not l.startswith("plot:")]
        assert printed == wanted, f"block {i} printed:\n{done.stdout}"
