#!/usr/bin/env bash
# Device call 1 of 2026-12-03 (ninth session), all measurements in one call. N = c9e806b (lean bundle), A = 5fbfd8c (last round's
# final build). Images of N against A; cold thumbnails N / N with 12 scene parsers / A alternated
# (is the parse throughput a limit? 8 parsers at 7-9 ms per parse is about 1,000/s); warm N;
# the 10,000-request soak with upload staging on (128 MiB of pinned mapped memory); 720p; start-up.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
echo "== images, N against A"
timeout 120 python3 scripts/check-frame-overlap --lghd .devbundle/bin/lghd --assets .assets --copies 2 \
  --against-lghd .devbundle-a/lghd-5fbfd8c -- --require-gpu 2>&1 | tail -4
for run in n1 p1 a1 n2 p2 a2 n3 p3 a3; do
  bin=.devbundle/bin/lghd; extra=
  case $run in
    p*) extra="--scene-parsers 12";;
    a*) bin=.devbundle-a/lghd-5fbfd8c;;
  esac
  echo "== $run $bin $extra"
  timeout 100 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d --rounds 5 \
    --copies 10 --cache off --json /tmp/thumbs_$run.json -- --require-gpu $extra 2>&1 | grep -E 'thumbnails/s'
  python3 - "/tmp/thumbs_$run.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))["lghd_cache_off"]["stages"]
m = d["ms_per_thumbnail"]
print(f"  parse {m['parse']:.2f} upload {m['upload']:.3f} submit {m['submit']:.3f} scene_wait {m['scene_wait']:.3f}"
      f" gbuffer {d['issue_ms_per_thumbnail']['gbuffer']:.3f} release {m['scene_release']:.3f}")
PY
done
echo "== warm N"
timeout 100 python3 scripts/bench-thumbnails --lghd .devbundle/bin/lghd --assets .assets --no-f3d --rounds 5 \
  --copies 10 --cache warm --json /tmp/thumbs_warm.json -- --require-gpu 2>&1 | grep -E 'thumbnails/s'
tar -C /tmp -czf $OUT/call1_thumbs.tgz $(cd /tmp && ls thumbs_*.json)

echo "== soak, default settings (N)"
timeout 300 python3 scripts/soak --lghd .devbundle/bin/lghd --asset-root .assets --renders 10000 \
  --json $OUT/call1_soak.json -- --require-gpu 2>&1 | tail -25
echo "== 720p PNG level 6 (N)"
timeout 120 python3 scripts/bench-output --lghd .devbundle/bin/lghd --width 1280 --height 720 --level 6 \
  --requests 30 --clients 16 --duration 15 -- --require-gpu 2>&1 | tail -12
echo "== start-up (N)"
timeout 100 scripts/bench-startup --runs 5 .devbundle/bin/lghd --require-gpu 2>&1 | tail -4
uptime
} > $OUT/call1.log 2>&1
