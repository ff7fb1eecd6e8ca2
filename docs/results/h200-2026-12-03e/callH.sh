#!/usr/bin/env bash
# Device call H of 2026-12-03 (eleventh session): how long Z's render thread (535680c, the
# bundle's binary with its symbols) sleeps during two cold batches, and where
# (offcpu_sched.py as changed after call G: the switches off with stacks from a per-thread session, the switches back on from a machine-wide one without stacks).
set -u
mkdir -p /tmp/p && tar -C /tmp/p -xJf .devbundle-p/perf.tar.xz
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
timeout 400 python3 .devbundle-p/offcpu_sched.py .devbundle/bin/lghd .assets --require-gpu 2>&1 | grep -v "^\[ perf"
uptime
} > $OUT/callH.log 2>&1
