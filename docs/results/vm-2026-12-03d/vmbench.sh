#!/usr/bin/env bash
# The 2-core VM (llvmpipe + lavapipe), twelfth session: lean bundles of K = 51c5e89 and
# C = 0c1f641, cold, alternated four times; run from the repository root.
set -u
for r in 1 2 3 4; do
  for v in k11 c12; do
    echo "== $v run $r"
    LD_LIBRARY_PATH=/work/bundle-tree/.devbundle-$v/lib python3 scripts/bench-thumbnails \
      --lghd /work/bundle-tree/.devbundle-$v/bin/lghd --assets /usr/share/assimp/models/glTF2 \
      --no-f3d --rounds 5 --cache off --json docs/results/vm-2026-12-03d/thumbs_${v}_$r.json 2>&1 | grep -E 'thumbnails/s'
  done
done
uptime
