#!/usr/bin/env bash
# Device call G of 2026-12-03 (eleventh session): how long Z's render thread (535680c, the
# bundle's binary with its symbols) sleeps during two cold batches, and where
# (offcpu_sched.py as it was at 32e7c34..this call: perf sched record, every switch paired with the
# one that gives the CPU back; changed for call H).
set -u
mkdir -p /tmp/p && tar -C /tmp/p -xJf .devbundle-p/perf.tar.xz
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
timeout 400 python3 .devbundle-p/offcpu_sched.py .devbundle/bin/lghd .assets --require-gpu 2>&1 | grep -v "^\[ perf"
uptime
} > $OUT/callG.log 2>&1
