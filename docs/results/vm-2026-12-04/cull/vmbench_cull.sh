# The 2-core VM, 2026-12-04: F = b4138b3 against G = 3fb4773 (no shadow ray where a direct light
# cannot light the surface), lean Release builds, four alternated pairs (run from the checkout).
for pair in 1 2 3 4; do
  for name in f g; do
    bin=${LGHD_DIR:?the folder of lghd-f and lghd-g}/lghd-$name
    echo "== $name$pair"
    scripts/bench-thumbnails --lghd "$bin" --assets /usr/share/assimp/models/glTF2 --no-f3d \
      --rounds 5 --cache off --json "docs/results/vm-2026-12-04/cull/thumbs_$name$pair.json" 2>&1 | grep -E 'thumbnails/s'
  done
done
