#!/bin/bash
# Sixteenth session, the 2-core VM: alternated pairs of the round's start (B = 7f83e3d, its lean
# Release build kept aside) and its end (N = ed4e2a3's lean build), cold and warm:
#   bash docs/results/vm-2026-12-04c/vmbench.sh BASE_LGHD NEW_LGHD
set -euo pipefail
base=$1; new=$2; out=docs/results/vm-2026-12-04c
assets=/usr/share/assimp/models/glTF2
for i in 1 2 3 4 5; do
  for which in B N; do
    bin=$base; [ $which = N ] && bin=$new
    scripts/bench-thumbnails --lghd "$bin" --assets $assets --no-f3d --rounds 5 --cache off \
      --json $out/cold_${which}$i.json 2>&1 >/dev/null | grep -E "thumbnails/s" | sed "s/^/$which$i /"
  done
done
for i in 1 2; do
  for which in B N; do
    bin=$base; [ $which = N ] && bin=$new
    scripts/bench-thumbnails --lghd "$bin" --assets $assets --no-f3d --rounds 5 --cache warm \
      --json $out/warm_${which}$i.json 2>&1 >/dev/null | grep -E "thumbnails/s" | sed "s/^/$which$i /"
  done
done
# CPU per thumbnail by thread and the idle share of both CPUs, each build (cold batches of the
# asset list three times over).
for which in B N; do
  bin=$base; [ $which = N ] && bin=$new
  echo "== $which CPU"; python3 docs/results/h200-2026-12-03f/cpu_split.py "$bin" $assets 3
  echo "== $which idle"; python3 docs/results/vm-2026-12-04b/idle_batch.py "$bin" --scene-cache-mb 0
done
