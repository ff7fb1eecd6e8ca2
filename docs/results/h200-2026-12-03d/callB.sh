#!/usr/bin/env bash
# Device call B of 2026-12-03 (tenth session): acceleration-structure storage recycled across
# scenes (P) against the session's starting point c5d5b3b (B), cold thumbnails alternated; P with
# 8 encoders; P with every release held (the ceiling of removing the frees); warm P; images P
# against B; who P's render thread still waits for; its call stacks for reading off-device.
set -u
mkdir -p /tmp/p && tar -C /tmp/p -xJf .devbundle-p/perf.tar.xz
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
bench() {  # name binary extra-lghd-args env...
  local name=$1 bin=$2 extra=$3; shift 3
  echo "== $name"
  env X=1 "$@" timeout 60 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache ${CACHE:-off} --json /tmp/thumbs_$name.json -- --require-gpu $extra 2>&1 | grep -E 'thumbnails/s'
  python3 - "/tmp/thumbs_$name.json" <<'PY'
import json, sys
try:
    d = json.load(open(sys.argv[1]))["lghd_cache_off"]["stages"]
    m = d["ms_per_thumbnail"]
    print(f"  parse {m['parse']:.2f} upload {m['upload']:.3f} submit {m['submit']:.3f} scene_wait {m['scene_wait']:.3f}"
          f" gbuffer {d['issue_ms_per_thumbnail']['gbuffer']:.3f} release {m['scene_release']:.3f}")
except Exception as e:
    print("  no stages:", e)
PY
}
B=.devbundle/bin/lghd-base; P=.devbundle/bin/lghd
for r in 1 2 3; do
  bench base$r $B ""
  bench pool$r $P ""
  [ $r -le 2 ] && bench pool_enc8_$r $P "--encode-threads 8"
  [ $r -le 2 ] && bench pool_hold$r $P "" LGH_EXP_AS_FREE=hold
done
CACHE=warm bench pool_warm $P ""
tar -C /tmp -czf $OUT/callB_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
echo "== images, P against B"
timeout 120 python3 scripts/check-frame-overlap --lghd $P --assets .assets --copies 2 \
  --against-lghd $B -- --require-gpu 2>&1 | tail -4
echo "== co-running profile, P"
timeout 90 python3 .devbundle-p/corun.py pool 2>&1 | grep -v "^\[ perf"
echo "== render thread stacks, P"
timeout 120 python3 .devbundle-p/render_stacks.py pool 2>&1 | grep -v "^\[ perf"
uptime
} > $OUT/callB.log 2>&1
