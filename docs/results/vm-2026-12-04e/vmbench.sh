#!/bin/bash
# Seventeenth session, the 2-core VM: five alternated pairs of B = 31dbb52 and N = e6f63f3 (the
# session's final code; lean Release builds), cold, then two warm: bash docs/results/vm-2026-12-04e/vmbench.sh B_LGHD N_LGHD
set -euo pipefail
base=$1; new=$2; out=docs/results/vm-2026-12-04e
assets=/usr/share/assimp/models/glTF2
for cache in off warm; do
  rounds=5; [ $cache = warm ] && rounds=2
  for i in $(seq 1 $rounds); do
    for which in B N; do
      bin=$base; [ $which = N ] && bin=$new
      scripts/bench-thumbnails --lghd "$bin" --assets $assets --no-f3d --rounds 5 --cache $cache \
        --json $out/${cache}_${which}$i.json 2>&1 >/dev/null | grep -E "thumbnails/s" | sed "s/^/$which$i /"
    done
  done
done
