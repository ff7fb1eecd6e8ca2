#!/usr/bin/env bash
# Device call 2 of 2026-12-03 (ninth session), N = c9e806b: the 1280x720 PNG at level 6, one
# request and 16 clients (call 1's log lost the one-request line to its tail).
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
for run in 1 2; do
  echo "== 720p PNG level 6 (N), run $run"
  timeout 120 python3 scripts/bench-output --lghd .devbundle/bin/lghd --width 1280 --height 720 --level 6 \
    --requests 30 --clients 16 --duration 15 --json $OUT/call2_output_$run.json -- --require-gpu 2>&1 | grep -E "one client|clients:"
done
uptime
} > $OUT/call2.log 2>&1
