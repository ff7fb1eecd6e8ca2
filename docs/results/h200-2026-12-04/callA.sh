#!/usr/bin/env bash
# Device call A of 2026-12-04 (fourteenth session): D = f7b7dda (the thirteenth round's code)
# against E = D + the pixel pack that packs four pixels per invocation with one integer division
# (glsl/pixel_pack.comp). E's images against D's (the same pixels expected: the pack moves the
# same codes; same_pixels.py compares them decoded), thumbnails through lghd and the demo at
# 1280x720 and 37x19 through lgh-render; cold thumbnails alternated; warm; 720p PNG level 6,
# one client and 16.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
D=.devbundle/bin/lghd-d; E=.devbundle/bin/lghd
RD=.devbundle/bin/lgh-render-d; RE=.devbundle/bin/lgh-render
bench() {  # name binary cache [lghd flags]
  local name=$1 bin=$2 cache=$3; shift 3
  echo "== $name"
  timeout 60 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $cache --json /tmp/thumbs_$name.json -- --require-gpu "$@" 2>&1 | grep -E 'thumbnails/s'
}
echo "== images, E against D (thumbnails through lghd)"
timeout 120 python3 scripts/check-frame-overlap --lghd $E --assets .assets --copies 2 \
  --against-lghd $D -- --require-gpu 2>&1 | tail -4
echo "== images, E against D (lgh-render: the demo at 1280x720 and 37x19, RGB and RGBA)"
for size in "1280 720" "37 19"; do
  set -- $size
  for alpha in false true; do
    echo "{\"output\": {\"width\": $1, \"height\": $2, \"transparent_background\": $alpha}}" > /tmp/req.json
    $RD /tmp/req.json -o /tmp/d.png -q --require-gpu
    $RE /tmp/req.json -o /tmp/e.png -q --require-gpu
    echo "${1}x$2 alpha=$alpha $(python3 docs/results/h200-2026-12-04/same_pixels.py /tmp/d.png /tmp/e.png)"
  done
done
bench warmup $E off
for r in 1 2 3 4; do
  bench d$r $D off
  bench e$r $E off
done
bench e_warm1 $E warm
bench d_warm1 $D warm
bench e_warm2 $E warm
tar -C /tmp -czf $OUT/callA_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
for b in E D E; do
  echo "== 720p PNG level 6, $b"
  timeout 120 python3 scripts/bench-output --lghd ${!b} --width 1280 --height 720 --level 6 \
    --requests 30 --clients 16 --duration 12 -- --require-gpu 2>&1 | grep -E "one client|clients:"
done
uptime
} > $OUT/callA.log 2>&1
