#!/usr/bin/env bash
# Device call K of 2026-12-04 (nineteenth session): N = 801be07 (the code of 623dae5, the eighteenth
# round closed: surface tiles, unrolled light loops, smallest file first, and its review) against
# B = ea1a808 (the seventeenth round's code). N's images against B's (same_pixels.py compares
# them decoded), thumbnails through lghd and the demo at 1280x720 and 37x19 through lgh-render;
# cold thumbnails alternated; warm; 720p PNG level 6, one client and 16.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
B=.devbundle/bin/lghd-b; N=.devbundle/bin/lghd
RB=.devbundle/bin/lgh-render-b; RN=.devbundle/bin/lgh-render
bench() {  # name binary cache [lghd flags]
  local name=$1 bin=$2 cache=$3; shift 3
  echo "== $name"
  timeout 60 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $cache --json /tmp/thumbs_$name.json -- --require-gpu "$@" 2>&1 | grep -E 'thumbnails/s'
}
echo "== images, N against B (thumbnails through lghd)"
timeout 120 python3 scripts/check-frame-overlap --lghd $N --assets .assets --copies 2 \
  --against-lghd $B -- --require-gpu 2>&1 | tail -4
echo "== images, N against B (lgh-render: the demo at 1280x720 and 37x19, RGB and RGBA)"
for size in "1280 720" "37 19"; do
  set -- $size
  for alpha in false true; do
    echo "{\"output\": {\"width\": $1, \"height\": $2, \"transparent_background\": $alpha}}" > /tmp/req.json
    $RB /tmp/req.json -o /tmp/b.png -q --require-gpu
    $RN /tmp/req.json -o /tmp/n.png -q --require-gpu
    echo "${1}x$2 alpha=$alpha $(python3 docs/results/h200-2026-12-04c/same_pixels.py /tmp/b.png /tmp/n.png)"
  done
done
bench warmup $N off
for r in 1 2 3 4; do
  bench b$r $B off
  bench n$r $N off
done
bench n_warm1 $N warm
bench b_warm1 $B warm
bench n_warm2 $N warm
tar -C /tmp -czf $OUT/callK_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
for b in N B N; do
  echo "== 720p PNG level 6, $b"
  timeout 120 python3 scripts/bench-output --lghd ${!b} --width 1280 --height 720 --level 6 \
    --requests 30 --clients 16 --duration 12 -- --require-gpu 2>&1 | grep -E "one client|clients:"
done
uptime
} > $OUT/callK.log 2>&1
