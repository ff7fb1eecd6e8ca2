#!/usr/bin/env bash
# Device call E of 2026-12-03 (twelfth session): a fifth machine start for C = 0c1f641, cold only,
# eight runs after a first one.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
C=.devbundle/bin/lghd
for r in warmup 1 2 3 4 5 6 7 8; do
  echo "== c$r"
  timeout 60 python3 scripts/bench-thumbnails --lghd $C --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache off --json /tmp/thumbs_c$r.json -- --require-gpu 2>&1 | grep -E 'thumbnails/s'
done
tar -C /tmp -czf $OUT/callE_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
uptime
} > $OUT/callE.log 2>&1
