#!/usr/bin/env bash
# Device call G of 2026-12-03 (eleventh session): how long Z's render thread (535680c, the
# bundle's binary with its symbols) sleeps during two cold batches, and where
# (the first version of offcpu_sched.py, not kept: perf sched record of every scheduler event, each
# switch off paired with the next one back on; call H has the kept version).
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
