# Who holds the driver lock the render thread spins on? Cold thumbnails through one lghd,
# the whole process sampled by perf with timestamps; for each render-thread sample spinning in
# the kernel's rt_mutex slow path, the other threads' samples within +-WINDOW ms are counted by
# thread kind and library (the owner of a PI futex runs while its waiter spins).
import collections, importlib.machinery, importlib.util, os, re, subprocess, sys, time
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec)
loader.exec_module(bt)
perf = ["/tmp/p/bin/perf"]
env = dict(os.environ, LD_LIBRARY_PATH="/tmp/p/lib")
label = sys.argv[1]
WINDOW = 0.35e-3
d = bt.Daemon(os.environ.get("LGHD_BIN", ".devbundle/bin/lghd"), ".assets",
              ["--scene-cache-mb", "0", "--require-gpu"])
try:
    ok, failed = bt.renderable(d, bt.find_assets(".assets"), 256)
    batch = ok * 10
    d.thumbnails(batch, 256)
    pid = d.process.pid
    rec = subprocess.Popen(perf + ["record", "-q", "-o", f"/tmp/{label}.data", "-p", str(pid),
                                   "-F", "2999", "-T"], env=env)
    time.sleep(1.0)
    start = time.perf_counter()
    for _ in range(2):
        d.thumbnails(batch, 256)
    print(label, "2 batches of", len(batch), "in", round(time.perf_counter() - start, 3), "s", flush=True)
    rec.send_signal(2)
    rec.wait()
finally:
    d.stop()
out = subprocess.run(perf + ["script", "-i", f"/tmp/{label}.data", "-F", "comm,tid,time,ip,sym,dso"],
                     env=env, capture_output=True, text=True).stdout
line_re = re.compile(r"^\s*(\S.*?)\s+(\d+)\s+([\d.]+):\s+([0-9a-f]+)\s+(.*?)\s+\((.*)\)\s*$")
samples = []
for line in out.splitlines():
    m = line_re.match(line)
    if not m: continue
    comm, tid, t, ip, sym, dso = m.groups()
    kind = re.sub(r"-\d+$", "", comm.strip())
    samples.append((float(t), int(tid), kind, sym, os.path.basename(dso)))
samples.sort()
print(label, "samples", len(samples))
by_kind = collections.Counter(s[2] for s in samples)
print("  by thread kind:", ", ".join(f"{k} {v}" for k, v in by_kind.most_common(12)))
render = [s for s in samples if s[2] == "lgh-render"]
spin = [s for s in render if "rt_mutex" in s[3] or "vcpu_is_preempted" in s[3]]
print(f"  render samples {len(render)}, spinning {len(spin)} ({100*len(spin)/max(1,len(render)):.1f} %)")
def nearby(moments):
    import bisect
    times = [s[0] for s in samples]
    hits = collections.Counter(); where = collections.Counter()
    for m in moments:
        lo = bisect.bisect_left(times, m[0] - WINDOW); hi = bisect.bisect_right(times, m[0] + WINDOW)
        seen = set()
        for s in samples[lo:hi]:
            if s[1] == m[1] or s[1] in seen: continue
            seen.add(s[1])
            nv = "nvidia" in s[4] or s[4] in ("[kernel.kallsyms]", "libvulkan.so.1", "libGLdispatch.so.0")
            if not nv: continue
            hits[s[2]] += 1
            where[(s[2], s[4], s[3][:40])] += 1
    return hits, where
for name, moments in (("spinning", spin), ("not spinning", [s for s in render if s not in spin][:len(spin)])):
    hits, where = nearby(moments)
    print(f"  {name} moments {len(moments)}: threads in the driver or kernel within {WINDOW*1e3} ms:")
    for k, v in hits.most_common(8):
        print(f"    {k:16s} {v:5d}  ({100*v/max(1,len(moments)):.0f} % of moments)")
    print("    top places:")
    for (k, dso, sym), v in where.most_common(14):
        print(f"      {v:5d} {k:14s} {dso:34s} {sym}")
