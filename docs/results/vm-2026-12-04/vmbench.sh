#!/usr/bin/env bash
# The 2-core VM, 2026-12-04 (fourteenth session): D = f7b7dda against F = b4138b3 (the pixel
# pack's four pixels per invocation on llvmpipe), both lean Release builds (build-lean), cold
# thumbnails alternated in five pairs: bash vmbench.sh D_LGHD F_LGHD OUT_DIR
set -u
D=$1 F=$2 out=$3
for pair in 1 2 3 4 5; do
  for name in d f; do
    bin=$D; [ $name = f ] && bin=$F
    echo "== $name$pair"
    scripts/bench-thumbnails --lghd "$bin" --assets /usr/share/assimp/models/glTF2 --no-f3d \
      --rounds 5 --cache off --json "$out/thumbs_$name$pair.json" 2>&1 | grep -E 'thumbnails/s|ms per thumbnail'
  done
done
