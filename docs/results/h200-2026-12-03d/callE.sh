#!/usr/bin/env bash
# Device call E of 2026-12-03 (tenth session): the scene waits left on the cold render thread
# come from three large assets whose parse or build outlasts the look-ahead. T = 3e84668 with
# experiment knobs: LGH_EXP_PER_PROCESS / LGH_EXP_MAX_DEPTH (scenes hinted ahead per parser
# process and in all; 8 / 64 in T) and LGH_EXP_BUILDERS (builds ahead side by side; 4 in T).
set -u
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
lscpu | grep -E "Model name"
T=.devbundle/bin/lghd
bench() {  # name extra env...
  local name=$1 extra=$2; shift 2
  echo "== $name"
  env X=1 "$@" timeout 60 python3 scripts/bench-thumbnails --lghd $T --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache off --json /tmp/thumbs_$name.json -- --require-gpu $extra 2>&1 | grep -E 'thumbnails/s'
  python3 - "/tmp/thumbs_$name.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))["lghd_cache_off"]["stages"]
m = d["ms_per_thumbnail"]
print(f"  parse {m['parse']:.2f} upload {m['upload']:.3f} submit {m['submit']:.3f} scene_wait {m['scene_wait']:.3f}"
      f" gbuffer {d['issue_ms_per_thumbnail']['gbuffer']:.3f} release {m['scene_release']:.3f}")
PY
}
for r in 1 2; do
  bench t$r ""
  bench d128_$r "" LGH_EXP_PER_PROCESS=16 LGH_EXP_MAX_DEPTH=128
  bench b8_$r "" LGH_EXP_BUILDERS=8
  bench d128b8_$r "" LGH_EXP_PER_PROCESS=16 LGH_EXP_MAX_DEPTH=128 LGH_EXP_BUILDERS=8
done
bench p12d192b8 "--scene-parsers 12" LGH_EXP_PER_PROCESS=16 LGH_EXP_MAX_DEPTH=192 LGH_EXP_BUILDERS=8
bench t3 ""
tar -C /tmp -czf $OUT/callE_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
for v in t d128b8; do
  echo "== scene waits, $v (debug log, one cold run)"
  envs="X=1"; [ $v = d128b8 ] && envs="LGH_EXP_PER_PROCESS=16 LGH_EXP_MAX_DEPTH=128 LGH_EXP_BUILDERS=8"
  env $envs timeout 60 python3 scripts/bench-thumbnails --lghd $T --assets .assets --no-f3d --rounds 3 --copies 10 \
    --cache off --log-level debug -- --require-gpu 2>&1 | grep -E "scene cache: waited|vulkan: scene '2Cyl" > /tmp/waits_$v.txt
  python3 - /tmp/waits_$v.txt <<'PY'
import re, sys, collections
lines = open(sys.argv[1]).read().splitlines()
rows = [re.search(r"waited ([\d.]+) ms for the prefetched parse of (\S+) \(parse ([\d.]+) ms(?:, structures built ahead in ([\d.]+) ms)?", l) for l in lines]
rows = [r for r in rows if r]
print(len(rows), "waits of 1 ms or more; total", round(sum(float(r.group(1)) for r in rows), 1), "ms")
by = collections.defaultdict(list)
for r in rows: by[r.group(2).split("/")[-1][:40]].append((float(r.group(1)), float(r.group(3)), float(r.group(4) or -1)))
for k, v in sorted(by.items(), key=lambda kv: -sum(x[0] for x in kv[1]))[:8]:
    n = len(v)
    print(f"  {k:40s} {n:3d} waits, mean {sum(x[0] for x in v)/n:.2f} ms; parse {sum(x[1] for x in v)/n:.2f} ms; build ahead {sum(x[2] for x in v)/n:.2f} ms")
builds = [l for l in lines if "vulkan: scene" in l]
print("  2CylinderEngine builds:", len(builds)); [print("   ", b[b.find("vulkan:"):][:230]) for b in builds[:3]]
PY
done
uptime
} > $OUT/callE.log 2>&1
