# CPU seconds per thumbnail of each lghd thread and parser process over cold batches:
# python3 cpu_split.py LGHD ASSETS COPIES [LGHD FLAGS...] (the asset list COPIES times per batch).
import importlib.machinery, importlib.util, os, sys, time, collections
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec)
loader.exec_module(bt)
binary, assets_root, copies = sys.argv[1], sys.argv[2], int(sys.argv[3])
extra = sys.argv[4:]
tick = os.sysconf("SC_CLK_TCK")
def cpu_of(pid):
    out = collections.Counter()
    for t in os.listdir(f"/proc/{pid}/task"):
        try:
            comm = open(f"/proc/{pid}/task/{t}/comm").read().strip()
            f = open(f"/proc/{pid}/task/{t}/stat").read().rsplit(")", 1)[1].split()
            out[comm + ":" + t] += (int(f[11]) + int(f[12])) / tick
        except OSError:
            pass
    return out
def children(pid):
    kids = []
    for t in os.listdir(f"/proc/{pid}/task"):
        try: kids += [int(c) for c in open(f"/proc/{pid}/task/{t}/children").read().split()]
        except OSError: pass
    return kids
def snapshot(pid):
    s = cpu_of(pid)
    for k in children(pid):
        for name, v in cpu_of(k).items(): s["child:" + name] += v
    return s
d = bt.Daemon(binary, assets_root, ["--scene-cache-mb", "0", *extra])
try:
    ok, failed = bt.renderable(d, bt.find_assets(assets_root), 256)
    batch = ok * copies
    d.thumbnails(batch, 256)
    before = snapshot(d.process.pid); start = time.perf_counter()
    for _ in range(3): d.thumbnails(batch, 256)
    wall = time.perf_counter() - start
    after = snapshot(d.process.pid)
    n = len(batch) * 3
    print(f"{n} thumbnails in {wall:.2f} s ({n/wall:.1f}/s); CPU ms per thumbnail by thread:")
    groups = collections.Counter()
    for k in set(after) | set(before):
        name = k.split(":")[-2] if k.startswith("child:") else k.split(":")[0]
        groups[("child:" if k.startswith("child:") else "") + name.rstrip("0123456789-")] += after[k] - before[k]
    total = sum(groups.values())
    print(f"  all threads {1000*total/n:.2f} ms per thumbnail, {total/wall:.1f} cores busy")
    for k, v in groups.most_common(12):
        if v > 0: print(f"  {k:28s} {1000*v/n:7.3f}")
finally:
    d.stop()
