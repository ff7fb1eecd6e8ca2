#!/usr/bin/env bash
# Device call E of 2026-12-03 (eleventh session): where Z's render thread (535680c) waits off its
# CPU during two cold batches (offcpu.py: sched_switch events of that thread with user stacks).
set -u
mkdir -p /tmp/p && tar -C /tmp/p -xJf .devbundle-p/perf.tar.xz
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
timeout 200 python3 .devbundle-p/offcpu.py .devbundle/bin/lghd .assets --require-gpu 2>&1 | grep -v "^\[ perf"
uptime
} > $OUT/callE.log 2>&1
