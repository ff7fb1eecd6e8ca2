#!/usr/bin/env bash
# Device call I of 2026-12-03 (eleventh session): K = 51c5e89 (the task pool's workers sleep on a
# semaphore: the render thread no longer signals a condition variable per frame) against
# Z = 535680c, cold alternated; K's images against Z's; warm; 720p with 16 clients; where K's
# render thread sleeps (offcpu_sched.py, K's binary with its symbols).
set -u
mkdir -p /tmp/p && tar -C /tmp/p -xJf .devbundle-p/perf.tar.xz
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
Z=.devbundle/bin/lghd-z; K=.devbundle/bin/lghd
bench() {  # name binary cache
  local name=$1 bin=$2 cache=$3
  echo "== $name"
  timeout 60 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $cache --json /tmp/thumbs_$name.json -- --require-gpu 2>&1 | grep -E 'thumbnails/s'
}
echo "== images, K against Z"
timeout 120 python3 scripts/check-frame-overlap --lghd $K --assets .assets --copies 2 \
  --against-lghd $Z -- --require-gpu 2>&1 | tail -3
bench warmup $K off
for r in 1 2 3 4; do
  bench z$r $Z off
  bench k$r $K off
done
bench k_warm $K warm
bench z_warm $Z warm
tar -C /tmp -czf $OUT/callI_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
echo "== 720p PNG level 6, K"
timeout 120 python3 scripts/bench-output --lghd $K --width 1280 --height 720 --level 6 \
  --requests 30 --clients 16 --duration 12 -- --require-gpu 2>&1 | grep -E "one client|clients:"
echo "== where K's render thread sleeps"
timeout 200 python3 .devbundle-p/offcpu_sched.py $K .assets --require-gpu 2>&1 | grep -v "^\[ perf" | head -8
uptime
} > $OUT/callI.log 2>&1
