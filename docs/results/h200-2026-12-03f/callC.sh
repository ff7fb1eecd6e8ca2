#!/usr/bin/env bash
# Device call C of 2026-12-03 (twelfth session): which half of A = 50df0db counts. AR = A without
# the pool's change (the answer arena only: 50df0db with 51c5e89's scene_worker_pool.*), PO = A
# without the arena (the pool waking only the turn served: 50df0db with 51c5e89's scene_worker.*,
# scene_wire.cpp and renderer_options.hpp), against K = 51c5e89 and C = 0c1f641, cold alternated;
# a third machine start for C.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
K=.devbundle/bin/lghd-k; AR=.devbundle/bin/lghd-ar; PO=.devbundle/bin/lghd-po; C=.devbundle/bin/lghd
bench() {  # name binary cache [lghd flags]
  local name=$1 bin=$2 cache=$3; shift 3
  echo "== $name"
  timeout 60 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $cache --json /tmp/thumbs_$name.json -- --require-gpu "$@" 2>&1 | grep -E 'thumbnails/s'
}
bench warmup $C off
for r in 1 2 3; do
  bench k$r $K off
  bench ar$r $AR off
  bench po$r $PO off
  bench c$r $C off
done
bench c4 $C off
bench c5 $C off
tar -C /tmp -czf $OUT/callC_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
uptime
} > $OUT/callC.log 2>&1
