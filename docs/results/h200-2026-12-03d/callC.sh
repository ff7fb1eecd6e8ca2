#!/usr/bin/env bash
# Device call C of 2026-12-03 (tenth session): C = recycled structure storage + blended-surface
# centres computed when needed + the CPU count read once, against B = c5d5b3b; C's helper threads
# (encoders, prefetch) at nice 10 (LGH_EXP_NICE), with 8 encoders, with 16 frames in flight;
# warm; 720p with 16 clients for the same variants; the CPU topology; C's render-thread stacks.
set -u
mkdir -p /tmp/p && tar -C /tmp/p -xJf .devbundle-p/perf.tar.xz
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
lscpu | grep -E "Model name|Thread|Core|Socket|NUMA node\(s\)"
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
B=.devbundle/bin/lghd-base; C=.devbundle/bin/lghd
for r in 1 2; do
  bench base$r $B ""
  bench c$r $C ""
  bench c_nice$r $C "" LGH_EXP_NICE=10
  bench c_enc8_$r $C "--encode-threads 8"
  bench c_fif16_$r $C "--frames-in-flight 16"
  bench c_p12_$r $C "--scene-parsers 12"
done
bench c3 $C ""
bench c_nice3 $C "" LGH_EXP_NICE=10
CACHE=warm bench c_warm1 $C ""
CACHE=warm bench c_nice_warm1 $C "" LGH_EXP_NICE=10
tar -C /tmp -czf $OUT/callC_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
for v in default nice enc8; do
  echo "== 720p PNG level 6, C $v"
  extra=; envs="X=1"
  [ $v = nice ] && envs="LGH_EXP_NICE=10"
  [ $v = enc8 ] && extra="--encode-threads 8"
  env $envs timeout 120 python3 scripts/bench-output --lghd $C --width 1280 --height 720 --level 6 \
    --requests 30 --clients 16 --duration 12 -- --require-gpu $extra 2>&1 | grep -E "one client|clients:"
done
echo "== render thread stacks, C"
timeout 120 python3 .devbundle-p/render_stacks.py c 2>&1 | grep -v "^\[ perf"
uptime
} > $OUT/callC.log 2>&1
