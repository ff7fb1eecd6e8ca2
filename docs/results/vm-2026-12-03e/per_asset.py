# The render thread's time per asset in cold batches on the VM (three NDJSON rounds, means): its
# submit, upload and the issue times of the frame's passes, and the shadow trace's time (lavapipe).
# python3 per_asset.py LGHD ASSETS_DIR, run from the repository root. Assets that share a file name
# (the four BoxTextured.gltf variants) are summed under it.
import importlib.machinery, importlib.util, sys, json, collections
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec)
loader.exec_module(bt)
binary, assets_root = sys.argv[1], sys.argv[2]
d = bt.Daemon(binary, assets_root, ["--scene-cache-mb", "0"])
try:
    ok, failed = bt.renderable(d, bt.find_assets(assets_root), 256)
    d.thumbnails(ok, 256)
    per = collections.defaultdict(collections.Counter)
    for r in range(3):
        _, _, data = d.thumbnails(ok, 256, "ndjson")
        for line in data.decode().splitlines():
            e = json.loads(line)
            if e.get("status") != "ok": continue
            a = e["asset"].split("/")[-1]
            for row in e["timings"]:
                if row.get("depth", 0): continue
                if row["pass"] in ("submit", "upload"): per[a][row["pass"]] += row["ms"] / 3
                if "cpu_ms" in row: per[a][row["pass"] + "*"] += row["cpu_ms"] / 3
                if row["pass"] == "shadow rays": per[a]["trace"] += row["ms"] / 3
    cols = ["submit", "upload", "gbuffer*", "shadow ray setup*", "direct lighting*", "readback*", "trace"]
    print(f"{'asset':34s} " + " ".join(f"{c[:10]:>10s}" for c in cols))
    tot = collections.Counter()
    for a, c in sorted(per.items(), key=lambda kv: -kv[1]["submit"]):
        print(f"{a[:34]:34s} " + " ".join(f"{c[k]:10.2f}" for k in cols)); tot.update(c)
    print(f"{'TOTAL':34s} " + " ".join(f"{tot[k]:10.2f}" for k in cols))
finally:
    d.stop()
