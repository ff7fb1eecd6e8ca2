#!/usr/bin/env bash
# Device call 3 of 2026-12-03 (ninth session): where the render thread's time goes in cold
# thumbnails (HEAD f68f064 bundle, thread names), with perf 6.1 carried from the dev VM.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
P="env LD_LIBRARY_PATH=$PWD/.devbundle-p/lib $PWD/.devbundle-p/bin/perf"
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
$P --version; cat /proc/sys/kernel/perf_event_paranoid
timeout 200 python3 .devbundle-p/profile.py
echo "== whole process, by thread"
$P report -i /tmp/process.data --no-children --sort comm --stdio -g none 2>/dev/null | grep -v '^#' | grep -v '^$' | head -30
echo "== render thread, by library"
$P report -i /tmp/render.data --no-children --sort dso --stdio -g none 2>/dev/null | grep -v '^#' | grep -v '^$' | head -25
echo "== render thread, leaf functions"
$P report -i /tmp/render.data --no-children --sort dso,sym --stdio -g none 2>/dev/null | grep -v '^#' | grep -v '^$' | head -50
echo "== render thread, inclusive (lghd's functions)"
$P report -i /tmp/render.data --children --sort sym --stdio -g none 2>/dev/null | grep -v '^#' | grep -v '^$' | grep -E 'lgh|lghd' | head -90
uptime
} > $OUT/call3.log 2>&1
