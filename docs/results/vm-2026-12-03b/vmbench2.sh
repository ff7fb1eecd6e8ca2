set -u
cd /work/main
for r in 1 2; do
  for v in t f; do
    b=/work/bundle-tree/.devbundle-$v
    echo "== $v$r"
    LD_LIBRARY_PATH=$b/lib python3 scripts/bench-thumbnails --lghd $b/bin/lghd --assets /usr/share/assimp/models/glTF2 \
      --no-f3d --rounds 5 --cache off --json /work/tmp/vm2_$v$r.json 2>&1 | grep -E "thumbnails/s"
  done
done
