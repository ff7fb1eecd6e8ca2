# The 2-core VM (llvmpipe + lavapipe), lean bundles: T = a7dc9a6, Z = 535680c, alternated.
set -u
cd /work/main
for r in 1 2 3; do
  for v in t11 z11; do
    b=/work/bundle-tree/.devbundle-$v
    echo "== $v $r"
    LD_LIBRARY_PATH=$b/lib python3 scripts/bench-thumbnails --lghd $b/bin/lghd --assets /usr/share/assimp/models/glTF2 \
      --no-f3d --rounds 5 --cache off --json docs/results/vm-2026-12-03c/vm_${v}_$r.json 2>&1 | grep -E "thumbnails/s"
  done
done
