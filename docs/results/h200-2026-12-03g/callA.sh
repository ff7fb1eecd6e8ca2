#!/usr/bin/env bash
# Device call A of 2026-12-03 (thirteenth session): C = 0c1f641 (the twelfth round's code) against
# D = a284334 (staging trace submitted without waiting, the sRGB code guessed then settled, frames
# with nothing to composite written by their direct lighting pass), cold alternated; D's images
# against C's; warm; 720p with 16 clients; where the machine's CPU goes in D's cold run.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
C=.devbundle/bin/lghd-c; D=.devbundle/bin/lghd
bench() {  # name binary cache [lghd flags]
  local name=$1 bin=$2 cache=$3; shift 3
  echo "== $name"
  timeout 60 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $cache --json /tmp/thumbs_$name.json -- --require-gpu "$@" 2>&1 | grep -E 'thumbnails/s'
}
echo "== images, D overlapped against D whole (--no-frame-overlap)"
timeout 120 python3 scripts/check-frame-overlap --lghd $D --assets .assets --copies 2 \
  -- --require-gpu 2>&1 | tail -2
echo "== images, D against C (one step of difference expected where the composite is skipped)"
timeout 120 python3 scripts/check-frame-overlap --lghd $D --assets .assets --copies 2 \
  --against-lghd $C -- --require-gpu 2>&1 | tail -4
bench warmup $D off
for r in 1 2 3 4; do
  bench c$r $C off
  bench d$r $D off
done
bench d_warm1 $D warm
bench d_warm2 $D warm
bench c_warm $C warm
tar -C /tmp -czf $OUT/callA_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
echo "== 720p PNG level 6, D"
timeout 120 python3 scripts/bench-output --lghd $D --width 1280 --height 720 --level 6 \
  --requests 30 --clients 16 --duration 12 -- --require-gpu 2>&1 | grep -E "one client|clients:"
echo "== CPU split, D cold"
timeout 100 python3 docs/results/h200-2026-12-03f/cpu_split.py $D .assets 10 --require-gpu 2>&1 | tail -14
uptime
} > $OUT/callA.log 2>&1
