#!/usr/bin/env bash
# Device call G of 2026-12-03 (tenth session): more cold runs of F (2c38c3c's code) beside T
# (3e84668), to see the spread around the 1,000/s target.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
lscpu | grep -E "Model name"
T=.devbundle/bin/lghd-t; F=.devbundle/bin/lghd
for run in t1 f1 f2 t2 f3 f4; do
  bin=$F; [ ${run:0:1} = t ] && bin=$T
  echo "== $run"
  timeout 60 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache off --json /tmp/thumbs_$run.json -- --require-gpu 2>&1 | grep -E 'thumbnails/s'
done
tar -C /tmp -czf $OUT/callG_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
uptime
} > $OUT/callG.log 2>&1
