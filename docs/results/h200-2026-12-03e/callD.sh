#!/usr/bin/env bash
# Device call D of 2026-12-03 (eleventh session): Z = 535680c with the default eight scene parser
# processes against Z with 16 (call C hinted at more with the render thread faster), alternated;
# where the machine's CPU goes in a cold run with each (cpu_split.py: CPU ms per thumbnail by
# thread and parser process).
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
Z=.devbundle/bin/lghd
bench() {  # name cache extra-lghd-args
  local name=$1 cache=$2 extra=${3:-}
  echo "== $name"
  timeout 60 python3 scripts/bench-thumbnails --lghd $Z --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $cache --json /tmp/thumbs_$name.json -- --require-gpu $extra 2>&1 | grep -E 'thumbnails/s'
}
bench warmup off
for r in 1 2 3 4 5; do
  bench z_p8_$r off
  bench z_p16_$r off "--scene-parsers 16"
done
tar -C /tmp -czf $OUT/callD_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
for p in 8 16; do
  echo "== CPU by thread, $p parsers"
  timeout 120 python3 .devbundle-p/cpu_split.py $Z .assets 10 --require-gpu --scene-parsers $p 2>&1 | tail -14
done
uptime
} > $OUT/callD.log 2>&1
