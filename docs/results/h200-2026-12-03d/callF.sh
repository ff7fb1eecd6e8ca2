#!/usr/bin/env bash
# Device call F of 2026-12-03 (tenth session): F = 3e84668 + the render worker drawing a batch's
# ready scenes ahead of one still being parsed, against T = 3e84668: images, cold thumbnails
# alternated, warm, 720p, the scene waits left, and the 10,000-request soak.
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
lscpu | grep -E "Model name"
T=.devbundle/bin/lghd-t; F=.devbundle/bin/lghd
echo "== images, F against T"
timeout 120 python3 scripts/check-frame-overlap --lghd $F --assets .assets --copies 2 \
  --against-lghd $T -- --require-gpu 2>&1 | tail -2
bench() {  # name binary cache
  echo "== $1"
  timeout 60 python3 scripts/bench-thumbnails --lghd $2 --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $3 --json /tmp/thumbs_$1.json -- --require-gpu 2>&1 | grep -E 'thumbnails/s'
  [ $3 = off ] && python3 - "/tmp/thumbs_$1.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))["lghd_cache_off"]["stages"]
m = d["ms_per_thumbnail"]
print(f"  parse {m['parse']:.2f} upload {m['upload']:.3f} submit {m['submit']:.3f} scene_wait {m['scene_wait']:.3f}"
      f" gbuffer {d['issue_ms_per_thumbnail']['gbuffer']:.3f} release {m['scene_release']:.3f}")
PY
}
bench t1 $T off; bench f1 $F off; bench t2 $T off; bench f2 $F off; bench t3 $T off; bench f3 $F off
bench f_warm1 $F warm; bench t_warm1 $T warm; bench f_warm2 $F warm
tar -C /tmp -czf $OUT/callF_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
echo "== 720p PNG level 6, F"
timeout 120 python3 scripts/bench-output --lghd $F --width 1280 --height 720 --level 6 \
  --requests 30 --clients 16 --duration 15 -- --require-gpu 2>&1 | grep -E "one client|clients:"
echo "== scene waits of F (debug log, one cold run)"
timeout 60 python3 scripts/bench-thumbnails --lghd $F --assets .assets --no-f3d --rounds 3 --copies 10 \
  --cache off --log-level debug -- --require-gpu 2>&1 | grep "scene cache: waited" > /tmp/waits.txt
python3 - <<'PY'
import re, collections
rows = [re.search(r"waited ([\d.]+) ms for the prefetched parse of (\S+) \(parse ([\d.]+) ms(?:, structures built ahead in ([\d.]+) ms)?", l) for l in open("/tmp/waits.txt")]
rows = [r for r in rows if r]
print(len(rows), "waits of 1 ms or more; total", round(sum(float(r.group(1)) for r in rows), 1), "ms")
by = collections.defaultdict(list)
for r in rows: by[r.group(2).split("/")[-1][:40]].append((float(r.group(1)), float(r.group(3)), float(r.group(4) or -1)))
for k, v in sorted(by.items(), key=lambda kv: -sum(x[0] for x in kv[1]))[:8]:
    n = len(v)
    print(f"  {k:40s} {n:3d} waits, mean {sum(x[0] for x in v)/n:.2f} ms; parse {sum(x[1] for x in v)/n:.2f} ms; build ahead {sum(x[2] for x in v)/n:.2f} ms")
PY
echo "== soak, F"
timeout 300 python3 scripts/soak --lghd $F --asset-root .assets --renders 10000 \
  --json $OUT/callF_soak.json -- --require-gpu 2>&1 | tail -14
uptime
} > $OUT/callF.log 2>&1
