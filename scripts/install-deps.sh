#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs what mrhaptics needs, only what is missing. Idempotent, non-interactive.
# - Debian packages (apt-get).
# - MuJoCo: the PyPI `mujoco` wheel of the version pinned in scripts/mujoco-version.txt, unpacked
#   into build/deps (pip --target: the system's Python is not touched, so this also works where
#   pip is externally managed). CMake takes its C headers and libmujoco.so from there
#   (cmake/MrhMujoco.cmake); MRH_DEPS_DIR overrides the folder.
# - The Python bindings' packages pinned in scripts/python-requirements.txt (pybind11, numpy,
#   pytest), for the python3 on PATH, into build/deps/python the same way: the build takes
#   pybind11 from there and the tests run with that folder on PYTHONPATH (cmake/MrhPython.cmake).
# Usage: scripts/install-deps.sh [--no-viewer]   (run as root, or with sudo available)
# The viewer's packages (GLFW, Dear ImGui, Xvfb for its headless tests and screenshots) are
# installed by default; --no-viewer leaves them out (the build then has no `mrh view`).
# --viewer is accepted for compatibility (it is the default).
set -euo pipefail

packages=(
  build-essential cmake pkg-config python3 python3-pip
  libfcl-dev libqhull-dev libeigen3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev
  gnuplot-nox
  clang-format-14  # the format check of `make format-check` and CI
)
viewer=1
for arg in "$@"; do
  case "$arg" in
    --viewer) viewer=1 ;;
    --no-viewer) viewer=0 ;;
    *) echo "install-deps: unknown option '$arg'; expected --no-viewer" >&2; exit 2 ;;
  esac
done
if [[ $viewer -eq 1 ]]; then
  packages+=(libglfw3-dev libimgui-dev xvfb xauth libosmesa6-dev libegl-dev
            libxtst6)  # libxtst6: scripted key presses (XTest) in the psychophysics window test
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} packages present"
else
  echo "install-deps: installing ${missing[*]}"
  sudo_cmd=()
  if [[ $(id -u) -ne 0 ]]; then
    command -v sudo >/dev/null || { echo "install-deps: run as root or install sudo" >&2; exit 1; }
    sudo_cmd=(sudo)
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

root="$(cd "$(dirname "$0")/.." && pwd)"
mujoco_version="$(head -n1 "$root/scripts/mujoco-version.txt")"
deps_dir="${MRH_DEPS_DIR:-$root/build/deps}"
if [[ -f "$deps_dir/mujoco/libmujoco.so.$mujoco_version" && -f "$deps_dir/mujoco/include/mujoco/mujoco.h" ]]; then
  echo "install-deps: MuJoCo $mujoco_version present in $deps_dir"
else
  echo "install-deps: installing MuJoCo $mujoco_version (PyPI wheel) into $deps_dir"
  rm -rf "$deps_dir/mujoco" "$deps_dir"/mujoco-*.dist-info
  mkdir -p "$deps_dir"
  python3 -m pip install -q --no-deps --no-warn-script-location --disable-pip-version-check \
    --root-user-action=ignore --target "$deps_dir" "mujoco==$mujoco_version"
fi

# Reinstalled when the pins or the interpreter change: the stamp holds both.
python_dir="$deps_dir/python"
python_stamp="$python_dir/.mrh-requirements"
python_want="$(python3 -c 'import sys; print(sys.implementation.cache_tag)'; \
               grep -v '^#' "$root/scripts/python-requirements.txt")"
if [[ -f "$python_stamp" && "$(cat "$python_stamp")" == "$python_want" ]]; then
  echo "install-deps: Python packages present in $python_dir"
else
  echo "install-deps: installing the Python packages of scripts/python-requirements.txt into $python_dir"
  rm -rf "$python_dir"
  mkdir -p "$python_dir"
  python3 -m pip install -q --no-deps --no-warn-script-location --disable-pip-version-check \
    --root-user-action=ignore --target "$python_dir" -r "$root/scripts/python-requirements.txt"
  printf '%s\n' "$python_want" > "$python_stamp"
fi
