#!/usr/bin/env bash
# Device call A of 2026-12-03 (twelfth session): K = 51c5e89 (the eleventh round's final code)
# against A = 50df0db (parser answers in a per-worker arena, the pool waking only the turn served),
# B = 43ec6b1 (A, and drawing ahead as far as the scenes were hinted) and C = 0c1f641 (B, and the
# MikkTSpace tangents without node containers), cold alternated; C's images against K's; C with 16
# parsers; warm; 720p with 16 clients; where the machine's CPU goes in C's cold run.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
K=.devbundle/bin/lghd-k; A=.devbundle/bin/lghd-a; B=.devbundle/bin/lghd-b; C=.devbundle/bin/lghd
bench() {  # name binary cache [lghd flags]
  local name=$1 bin=$2 cache=$3; shift 3
  echo "== $name"
  timeout 60 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $cache --json /tmp/thumbs_$name.json -- --require-gpu "$@" 2>&1 | grep -E 'thumbnails/s'
}
echo "== images, C against K"
timeout 120 python3 scripts/check-frame-overlap --lghd $C --assets .assets --copies 2 \
  --against-lghd $K -- --require-gpu 2>&1 | tail -3
bench warmup $C off
for r in 1 2 3; do
  bench k$r $K off
  bench a$r $A off
  bench b$r $B off
  bench c$r $C off
done
bench c16_1 $C off --scene-parsers 16
bench c16_2 $C off --scene-parsers 16
bench c_warm $C warm
bench k_warm $K warm
tar -C /tmp -czf $OUT/callA_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
echo "== 720p PNG level 6, C"
timeout 120 python3 scripts/bench-output --lghd $C --width 1280 --height 720 --level 6 \
  --requests 30 --clients 16 --duration 12 -- --require-gpu 2>&1 | grep -E "one client|clients:"
echo "== CPU split, C cold"
timeout 100 python3 .devbundle-p/cpu_split.py $C .assets 10 --require-gpu 2>&1 | tail -14
uptime
} > $OUT/callA.log 2>&1
