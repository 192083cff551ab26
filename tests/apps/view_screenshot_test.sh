#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# Renders a session headless under Xvfb with `mrh view --frames` (or --at) and checks the
# screenshot.
# Usage: view_screenshot_test.sh MRH CHECKER SESSION OUT.png FRAMES|--at=T [CHECKS...]
# CHECKS are the checker's options (--panel, --force); --panel also shows the panel.
# Exits 77 (CTest: skipped) when xvfb-run is not installed.
set -u
mrh=$1 checker=$2 session=$3 out=$4 frames=$5
shift 5
if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "xvfb-run not found (apt-get install xvfb xauth): skipping"
  exit 77
fi
rm -f "$out"
hide=--hide-panel
for check in "$@"; do
  [ "$check" = "--panel" ] && hide=
done
case $frames in
  --*) when=$frames ;;
  *) when="--frames=$frames" ;;
esac
# 24-bit colour: xvfb-run's default screen depth is too shallow for the GL visual on some setups.
xvfb-run -a -s "-screen 0 1600x1000x24" \
  "$mrh" view "$session" "$when" --screenshot "$out" $hide || exit 1
"$checker" "$out" "$@"
