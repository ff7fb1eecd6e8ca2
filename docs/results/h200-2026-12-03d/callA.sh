#!/usr/bin/env bash
# Device call A of 2026-12-03 (tenth session): which thread holds the NVIDIA driver lock the cold
# render thread spins on, and what the cold rate is without each source of Vulkan work beside it.
set -u
mkdir -p /tmp/p && tar -C /tmp/p -xJf .devbundle-p/perf.tar.xz
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
bench() {  # name, env..., -- extra bench args
  local name=$1; shift
  echo "== $name"
  env "$@" timeout 60 python3 scripts/bench-thumbnails --lghd .devbundle/bin/lghd --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache off --json /tmp/thumbs_$name.json $BARGS -- --require-gpu $LARGS 2>&1 | grep -E 'thumbnails/s'
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
for round in 1 2; do
  BARGS= LARGS= bench base$round X=1
  BARGS='--settings {"shadows":"off"}' LARGS= bench unshadowed$round X=1
  BARGS= LARGS= bench free_inline$round LGH_EXP_AS_FREE=inline
  BARGS= LARGS= bench free_hold$round LGH_EXP_AS_FREE=hold
  BARGS= LARGS= bench ahead_off$round LGH_EXP_AHEAD_OFF=1
  BARGS= LARGS= bench hold_ahead_off$round LGH_EXP_AS_FREE=hold LGH_EXP_AHEAD_OFF=1
  BARGS= LARGS='--encode-threads 8' bench encode8_$round X=1
done
tar -C /tmp -czf $OUT/callA_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
echo "== co-running profile, default"
timeout 90 python3 .devbundle-p/corun.py base 2>&1 | grep -v "^\[ perf"
echo "== co-running profile, frees held"
LGH_EXP_AS_FREE=hold timeout 90 python3 .devbundle-p/corun.py hold 2>&1 | grep -v "^\[ perf"
uptime
} > $OUT/callA.log 2>&1
