#!/usr/bin/env bash
# Device call F of 2026-12-03 (eleventh session): three frame sets and ray lanes instead of two
# (an experiment build of 535680c, S: with overlapped frames a frame's targets are then those of
# the frame before last but one; LGH_EXP_SETS=2 makes it alternate between two as before), against
# Z = 535680c; cold alternated, S's images against Z's, warm S.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
Z=.devbundle/bin/lghd-z; S=.devbundle/bin/lghd
bench() {  # name binary cache env...
  local name=$1 bin=$2 cache=$3; shift 3
  echo "== $name"
  env X=1 "$@" timeout 60 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $cache --json /tmp/thumbs_$name.json -- --require-gpu 2>&1 | grep -E 'thumbnails/s'
  python3 - "/tmp/thumbs_$name.json" <<'PY'
import json, sys
try:
    j = json.load(open(sys.argv[1]))
    d = j.get("lghd_cache_off", j.get("lghd_cache_warm", {}))["stages"]
    m = d["ms_per_thumbnail"]
    print(f"  submit {m['submit']:.3f} slot_wait {m['slot_wait']:.3f} gbuffer {d['issue_ms_per_thumbnail']['gbuffer']:.3f}"
          f" frame_wait {m['frame_wait']:.2f} gpu {m['gpu']:.3f}")
except Exception as e:
    print("  no stages:", e)
PY
}
echo "== images, S against Z"
timeout 120 python3 scripts/check-frame-overlap --lghd $S --assets .assets --copies 2 \
  --against-lghd $Z -- --require-gpu 2>&1 | tail -3
bench warmup $S off
for r in 1 2 3 4; do
  bench z$r $Z off
  bench s3_$r $S off
  bench s2_$r $S off LGH_EXP_SETS=2
done
bench s3_warm $S warm
bench z_warm $Z warm
tar -C /tmp -czf $OUT/callF_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
uptime
} > $OUT/callF.log 2>&1
