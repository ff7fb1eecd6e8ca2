#!/usr/bin/env bash
# Device call C of 2026-12-03 (eleventh session): the round's final code Z = 535680c (Y = 618fdff
# + cache counters and the lghd_scene_storage_kept_bytes metric) against T = a7dc9a6, cold
# thumbnails alternated, Z also with --scene-parsers 12 and 16 (with the render thread faster,
# are the eight parser processes the limit now?), warm twice, 720p with 16 clients, Z's images
# against T's, the new metric after a cold batch.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
lscpu | grep -E "Model name"
T=.devbundle/bin/lghd-t; Z=.devbundle/bin/lghd
bench() {  # name binary cache extra-lghd-args
  local name=$1 bin=$2 cache=$3 extra=${4:-}
  echo "== $name"
  timeout 60 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $cache --json /tmp/thumbs_$name.json -- --require-gpu $extra 2>&1 | grep -E 'thumbnails/s'
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
echo "== images, Z against T"
timeout 120 python3 scripts/check-frame-overlap --lghd $Z --assets .assets --copies 2 \
  --against-lghd $T -- --require-gpu 2>&1 | tail -3
bench warmup $Z off
for r in 1 2 3 4; do
  bench t$r $T off
  bench z$r $Z off
  [ $r -lt 4 ] && bench z_p12_$r $Z off "--scene-parsers 12"
  [ $r -lt 4 ] && bench z_p16_$r $Z off "--scene-parsers 16"
done
for r in 1 2; do
  bench z_warm$r $Z warm
  bench t_warm$r $T warm
done
tar -C /tmp -czf $OUT/callC_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
echo "== 720p PNG level 6, Z"
timeout 120 python3 scripts/bench-output --lghd $Z --width 1280 --height 720 --level 6 \
  --requests 30 --clients 16 --duration 12 -- --require-gpu 2>&1 | grep -E "one client|clients:"
echo "== metrics, Z (kept storage after a cold batch)"
python3 - "$Z" <<'PY'
import importlib.machinery, importlib.util, sys, urllib.request
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec)
loader.exec_module(bt)
d = bt.Daemon(sys.argv[1], ".assets", ["--scene-cache-mb", "0", "--require-gpu"])
try:
    ok, failed = bt.renderable(d, bt.find_assets(".assets"), 256)
    d.thumbnails(ok * 3, 256)
    text = urllib.request.urlopen(f"http://127.0.0.1:{d.port}/metrics").read().decode()
    print("\n".join(l for l in text.splitlines() if "scene_storage_kept" in l or "scene_cache_bytes" in l))
finally:
    d.stop()
PY
uptime
} > $OUT/callC.log 2>&1
