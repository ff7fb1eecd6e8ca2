# The idle share of both CPUs (/proc/stat) over three cold batches of the asset list three times
# over, after a warm-up batch: python3 idle_batch.py LGHD [LGHD FLAGS], e.g. --scene-cache-mb 0.
import importlib.machinery, importlib.util, sys, time
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec); loader.exec_module(bt)
def stat():
    out = {}
    for line in open('/proc/stat'):
        if line.startswith('cpu'):
            f = line.split(); out[f[0]] = list(map(int, f[1:]))
    return out
extra = sys.argv[2:]
d = bt.Daemon(sys.argv[1], '/usr/share/assimp/models/glTF2', extra)
try:
    ok, failed = bt.renderable(d, bt.find_assets('/usr/share/assimp/models/glTF2'), 256)
    batch = ok * 3
    d.thumbnails(batch, 256)
    a = stat(); t = time.perf_counter()
    for _ in range(3): d.thumbnails(batch, 256)
    wall = time.perf_counter() - t; b = stat()
    print(f"{3*len(batch)/wall:.1f}/s")
    names = ['user','nice','system','idle','iowait','irq','softirq','steal']
    for c in sorted(a):
        delta = [y - x for x, y in zip(a[c], b[c])]
        tot = sum(delta[:8])
        print(c, ' '.join(f"{n} {100*v/tot:.1f}%" for n, v in zip(names, delta[:8]) if v))
finally:
    d.stop()
