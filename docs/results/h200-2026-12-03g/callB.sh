#!/usr/bin/env bash
# Device call B of 2026-12-03 (thirteenth session): a second machine start for D = a284334, cold
# eight runs after a first one, warm twice, 720p.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
D=.devbundle/bin/lghd
bench() {  # name cache
  echo "== $1"
  timeout 60 python3 scripts/bench-thumbnails --lghd $D --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $2 --json /tmp/thumbs_$1.json -- --require-gpu 2>&1 | grep -E 'thumbnails/s'
}
for r in warmup 1 2 3 4 5 6 7 8; do bench d$r off; done
bench d_warm1 warm
bench d_warm2 warm
tar -C /tmp -czf $OUT/callB_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
echo "== 720p PNG level 6, D"
timeout 120 python3 scripts/bench-output --lghd $D --width 1280 --height 720 --level 6 \
  --requests 30 --clients 16 --duration 12 -- --require-gpu 2>&1 | grep -E "one client|clients:"
uptime
} > $OUT/callB.log 2>&1
