#!/usr/bin/env bash
# Device call B of 2026-12-03 (eleventh session): T = a7dc9a6 (the tenth round's end), W = 2caf690
# (uniforms only when they change, per-draw transforms as instanced attributes, RGBA8 texture
# storage kept across scenes), X = 2656923 (W + only changed texture units bound, the G-buffer's
# draw buffers only when they change), Y = 618fdff (X + geometry buffers kept across scenes).
# Cold thumbnails alternated; warm; 720p with 16 clients; Y's images against T's; the soak of
# 10,000 requests on Y (the kept storage must not grow); Y's render-thread stacks.
set -u
mkdir -p /tmp/p && tar -C /tmp/p -xJf .devbundle-p/perf.tar.xz
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
lscpu | grep -E "Model name"
T=.devbundle/bin/lghd-t; W=.devbundle/bin/lghd-w; X=.devbundle/bin/lghd-x; Y=.devbundle/bin/lghd
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
echo "== images, Y against T"
timeout 120 python3 scripts/check-frame-overlap --lghd $Y --assets .assets --copies 2 \
  --against-lghd $T -- --require-gpu 2>&1 | tail -3
bench warmup $Y off
for r in 1 2 3 4; do
  bench t$r $T off
  bench y$r $Y off
  bench x$r $X off
  bench w$r $W off
done
bench y_warm1 $Y warm
bench t_warm1 $T warm
bench y_warm2 $Y warm
bench t_warm2 $T warm
tar -C /tmp -czf $OUT/callB_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
echo "== 720p PNG level 6, Y"
timeout 120 python3 scripts/bench-output --lghd $Y --width 1280 --height 720 --level 6 \
  --requests 30 --clients 16 --duration 12 -- --require-gpu 2>&1 | grep -E "one client|clients:"
echo "== render thread stacks, Y"
LGHD_BIN=$Y timeout 120 python3 .devbundle-p/render_stacks.py y 2>&1 | grep -v "^\[ perf"
echo "== soak, Y"
timeout 300 python3 scripts/soak --lghd $Y --asset-root .assets --renders 10000 \
  --json $OUT/callB_soak.json -- --require-gpu 2>&1 | tail -14
uptime
} > $OUT/callB.log 2>&1
