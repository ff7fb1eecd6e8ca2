#!/usr/bin/env bash
# Device call B of 2026-12-03 (twelfth session): C = 0c1f641 against K = 51c5e89 again: warm
# alternated (call A's one warm pair had C 9 % below K), cold alternated (more runs of C), the
# 1280x720 PNG with one and 16 clients alternated, the soak of 10,000 requests on C (the answer
# arenas must not grow), and where C's render thread sleeps (offcpu_sched.py, C's binary with its
# symbols).
set -u
mkdir -p /tmp/p && tar -C /tmp/p -xJf .devbundle-p/perf.tar.xz
export LD_LIBRARY_PATH=$PWD/.devbundle/lib
nv=/usr/local/nvidia/share
export __EGL_VENDOR_LIBRARY_FILENAMES=$nv/glvnd/egl_vendor.d/10_nvidia.json VK_DRIVER_FILES=$nv/vulkan/icd.d/nvidia_icd.json
{
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader; nproc; uptime
K=.devbundle/bin/lghd-k; C=.devbundle/bin/lghd
bench() {  # name binary cache [lghd flags]
  local name=$1 bin=$2 cache=$3; shift 3
  echo "== $name"
  timeout 60 python3 scripts/bench-thumbnails --lghd $bin --assets .assets --no-f3d \
    --rounds 5 --copies 10 --cache $cache --json /tmp/thumbs_$name.json -- --require-gpu "$@" 2>&1 | grep -E 'thumbnails/s'
}
bench warmup $C off
for r in 1 2 3; do
  bench c_warm$r $C warm
  bench k_warm$r $K warm
done
for r in 1 2 3; do
  bench c${r}a $C off
  bench k$r $K off
  bench c${r}b $C off
done
tar -C /tmp -czf $OUT/callB_thumbs.tgz $(cd /tmp && ls thumbs_*.json)
for r in 1 2; do
  for v in C K; do
    echo "== 720p PNG level 6, $v"
    timeout 120 python3 scripts/bench-output --lghd ${!v} --width 1280 --height 720 --level 6 \
      --requests 30 --clients 16 --duration 12 -- --require-gpu 2>&1 | grep -E "one client:|clients:"
  done
done
echo "== soak, C"
timeout 300 python3 scripts/soak --lghd $C --asset-root .assets --renders 10000 \
  --json $OUT/callB_soak.json -- --require-gpu 2>&1 | tail -14
echo "== where C's render thread sleeps"
timeout 120 python3 .devbundle-p/offcpu_sched.py .devbundle/bin/lghd-csym .assets --require-gpu 2>&1 | grep -v "^\[ perf" | head -12
uptime
} > $OUT/callB.log 2>&1
