#!/usr/bin/env bash
# The 2-core VM, thirteenth session: C = 0c1f641 (twelfth round) against D = a284334, lean
# bundles, cold thumbnails alternated in pairs, then where the CPU goes in each (cpu_split.py).
# bash vmbench.sh C_BUNDLE D_BUNDLE
set -u
C=$1; D=$2; out=$(dirname "$0")
run() {  # name bundle
  LD_LIBRARY_PATH=$2/lib python3 scripts/bench-thumbnails --lghd $2/bin/lghd \
    --assets /usr/share/assimp/models/glTF2 --no-f3d --rounds 5 --cache off \
    --json $out/thumbs_$1.json 2>&1 | grep -E 'thumbnails/s' | sed "s/^/$1 /"
}
uptime
for r in 1 2 3 4 5 6; do run c$r $C; run d$r $D; done
for r in 1 2; do
  for v in c d; do
    b=$C; [ $v = d ] && b=$D
    echo "== cpu_split $v$r"
    LD_LIBRARY_PATH=$b/lib python3 docs/results/h200-2026-12-03f/cpu_split.py $b/bin/lghd \
      /usr/share/assimp/models/glTF2 3 2>&1 | head -9
  done
done
uptime
