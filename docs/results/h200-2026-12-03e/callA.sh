#!/usr/bin/env bash
# Device call A of 2026-12-03 (eleventh session): the render thread's per-draw cost. T = a7dc9a6
# (the tenth round's end), U = 1ba872f (uniforms set only when they change, multi-bind textures,
# fixed-function state only when it changes), V = U + per-draw transforms as instanced vertex
# attributes picked by the base instance (no uniform change between draws), W = 2caf690 (V + RGBA8
# texture storage kept across scenes). Cold thumbnails alternated; warm; 720p with 16 clients;
# W's images against T's; W's render-thread stacks.
set -u
mkdir -p /tmp/p && tar -C /tmp/p -xJf .devbundle-p/perf.tar.xz
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
lscpu | grep -E "Model name"
T=.devbundle/bin/lghd-t; U=.devbundle/bin/lghd-u; V=.devbundle/bin/lghd-v; W=.devbundle/bin/lghd
bench() {  # name binary cache
  local name=$1 bin=$2 cache=$3
  echo "== $name"
  timeout 60 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $cache --json /tmp/thumbs_$name.json -- --require-gpu 2>&1 | grep -E 'thumbnails/s'
  python3 - "/tmp/thumbs_$name.json" <<'PY'
import json, sys
try:
    j = json.load(open(sys.argv[1]))
    d = j.get("lghd_cache_off", j.get("lghd_cache_warm", {}))["stages"]
    m = d["ms_per_thumbnail"]
    print(f"  parse {m['parse']:.2f} upload {m['upload']:.3f} submit {m['submit']:.3f} scene_wait {m['scene_wait']:.3f}"
          f" gbuffer {d['issue_ms_per_thumbnail']['gbuffer']:.3f} release {m['scene_release']:.3f}")
except Exception as e:
    print("  no stages:", e)
PY
}
echo "== images, W against T"
timeout 120 python3 scripts/check-frame-overlap --lghd $W --assets .assets --copies 2 \
  --against-lghd $T -- --require-gpu 2>&1 | tail -3
for r in 1 2 3; do
  bench t$r $T off
  bench w$r $W off
  bench v$r $V off
  [ $r -lt 3 ] && bench u$r $U off
done
bench w_warm1 $W warm
bench t_warm1 $T warm
tar -C /tmp -czf $OUT/callA_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
echo "== 720p PNG level 6, W"
timeout 120 python3 scripts/bench-output --lghd $W --width 1280 --height 720 --level 6 \
  --requests 30 --clients 16 --duration 12 -- --require-gpu 2>&1 | grep -E "one client|clients:"
echo "== render thread stacks, W"
LGHD_BIN=$W timeout 120 python3 .devbundle-p/render_stacks.py w 2>&1 | grep -v "^\[ perf"
uptime
} > $OUT/callA.log 2>&1
