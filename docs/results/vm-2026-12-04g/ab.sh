#!/bin/bash
# Nineteenth session (a copy of vm-2026-12-04f/ab.sh): alternated cold runs of several lghd set-ups on the VM, each the median of
# R rounds (default 5) of the 31 thumbnails:
#   R=9 ab.sh PAIRS "LABEL|ENV|BINARY|LGHD FLAGS" ...   (ENV e.g. X=1 for none)
n=$1; shift
for i in $(seq 1 $n); do
  for spec in "$@"; do
    IFS='|' read -r label envs bin flags <<< "$spec"
    r=$(env $envs scripts/bench-thumbnails --lghd "$bin" --assets /usr/share/assimp/models/glTF2 --no-f3d --rounds ${R:-5} --cache off -- $flags 2>&1 >/dev/null | grep -E "thumbnails/s" | head -1)
    echo "$label$i $r"
  done
done
