#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# A person-with-a-mouse session of `mrh psychophysics run` under Xvfb, answered by scripted key
# presses (psychophysics_keys.py), then analysed: every trial of the design must be in
# trials.csv with the answers pressed, and `analyze` must write psychometric.json.
# Usage: psychophysics_window_test.sh MRH SESSION OUT_DIR
# Exits 77 (CTest: skipped) without xvfb-run, python3 or libXtst.
set -u
mrh=$1 session=$2 out=$3
here=$(dirname "$0")
for tool in xvfb-run python3; do
  if ! command -v $tool >/dev/null 2>&1; then
    echo "$tool not found (apt-get install xvfb xauth python3): skipping"
    exit 77
  fi
done
if ! python3 -c 'import ctypes.util, sys; sys.exit(not ctypes.util.find_library("Xtst"))'; then
  echo "libXtst not found (apt-get install libxtst6): skipping"
  exit 77
fi
rm -rf "$out"
# 2 masses x 2 trials of one method: 4 trials of 2 short stimuli each (SESSION: the small one).
xvfb-run -a -s "-screen 0 1280x1024x24" sh -c '
  "$1" psychophysics run "$2" --subject P --out "$3/P" --mouse \
    --set psychophysics.trials_per_mass=2 --set psychophysics.stimulus_duration=0.3 \
    --set psychophysics.pause=0.2 &
  pid=$!
  python3 "$4/psychophysics_keys.py" $pid 12 0.15 &
  keys=$!
  wait $pid; rc=$?
  kill $keys 2>/dev/null
  exit $rc' sh "$mrh" "$session" "$out" "$here" || { echo "run failed"; exit 1; }
trials="$out/P/trials.csv"
rows=$(tail -n +2 "$trials" | wc -l)
[ "$rows" -eq 4 ] || { echo "expected 4 trials in $trials, found $rows"; cat "$trials"; exit 1; }
# Answers are 1 or 2 and match comparison_heavier (checked again by analyze when it reads them).
"$mrh" psychophysics analyze "$trials" --out "$out/analysis" || exit 1
[ -s "$out/analysis/psychometric.json" ] || { echo "no psychometric.json"; exit 1; }
grep -q '"subject": "P"' "$out/analysis/psychometric.json" || exit 1
echo "ok: $rows trials answered by keys and analysed"
