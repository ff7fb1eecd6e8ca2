#!/bin/bash
# Fifteenth session, the 2-core VM: alternated pairs of the round's start (B = c7d2e62, a lean
# Release build in another worktree) and its end (N = this commit's lean build), cold and warm:
#   bash docs/results/vm-2026-12-04b/vmbench.sh BASE_LGHD NEW_LGHD
set -euo pipefail
base=$1; new=$2; out=docs/results/vm-2026-12-04b
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
