#!/usr/bin/env bash
# Device call D of 2026-12-03 (twelfth session): G = C (0c1f641) with the frame's five per-pixel
# compute passes in 16x16 work groups instead of 8x8 (faster on llvmpipe), against C on the H200:
# images, cold and warm alternated, 720p.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
C=.devbundle/bin/lghd; G=.devbundle/bin/lghd-g
bench() {  # name binary cache [lghd flags]
  local name=$1 bin=$2 cache=$3; shift 3
  echo "== $name"
  timeout 60 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $cache --json /tmp/thumbs_$name.json -- --require-gpu "$@" 2>&1 | grep -E 'thumbnails/s'
}
echo "== images, G against C"
timeout 120 python3 scripts/check-frame-overlap --lghd $G --assets .assets --copies 2 \
  --against-lghd $C -- --require-gpu 2>&1 | tail -3
bench warmup $G off
for r in 1 2 3; do
  bench c$r $C off
  bench g$r $G off
done
for r in 1 2; do
  bench c_warm$r $C warm
  bench g_warm$r $G warm
done
tar -C /tmp -czf $OUT/callD_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
for v in C G; do
  echo "== 720p PNG level 6, $v"
  timeout 120 python3 scripts/bench-output --lghd ${!v} --width 1280 --height 720 --level 6 \
    --requests 30 --clients 16 --duration 12 -- --require-gpu 2>&1 | grep -E "one client:|clients:"
done
uptime
} > $OUT/callD.log 2>&1
