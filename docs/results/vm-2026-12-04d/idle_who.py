# Seventeenth session: which thread runs while the other core idles, over two cold batches of
# the asset list three times over (machine-wide sched_switch; perf needs root or
# perf_event_paranoid <= 1): python3 idle_who.py LGHD [LGHD FLAGS], from the repository root.
# Machine-wide sched_switch over cold batches; idle time split by what the render thread was doing.
import importlib.machinery, importlib.util, os, re, subprocess, sys, time, collections
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec); loader.exec_module(bt)
binary, assets = sys.argv[1], '/usr/share/assimp/models/glTF2'
d = bt.Daemon(binary, assets, ["--scene-cache-mb", "0", *sys.argv[2:]])
try:
    ok, failed = bt.renderable(d, bt.find_assets(assets), 256)
    batch = ok * 3
    d.thumbnails(batch, 256)
    rec = subprocess.Popen(["perf", "record", "-q", "-a", "-o", "/tmp/idle_who.data", "-e", "sched:sched_switch", "-m", "4096"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(1.0)
    t0 = time.clock_gettime(time.CLOCK_MONOTONIC)
    for _ in range(2): d.thumbnails(batch, 256)
    t1 = time.clock_gettime(time.CLOCK_MONOTONIC)
    time.sleep(0.1)
    rec.send_signal(2); rec.wait()
    pid = d.process.pid
    import glob
    for p in [pid] + [int(x) for x in open(f"/proc/{pid}/task/{pid}/children").read().split()]:
        for t in os.listdir(f"/proc/{p}/task"):
            print("thread", p, t, open(f"/proc/{p}/task/{t}/comm").read().strip(), open(f"/proc/{p}/cmdline").read().replace(chr(0),' ')[:80] if int(t)==p else '')
finally:
    d.stop()
print(f"{2*len(batch)/(t1-t0):.1f}/s")
out = subprocess.run(["perf", "script", "-i", "/tmp/idle_who.data", "-F", "cpu,time,trace"], capture_output=True, text=True).stdout
sw = re.compile(r"\[(\d+)\]\s+([\d.]+):\s+prev_comm=(.*?) prev_pid=(\d+) .*?prev_state=(\S+) ==> next_comm=(.*?) next_pid=(\d+)")
ev = []
for line in out.splitlines():
    m = sw.search(line)
    if m: ev.append((float(m.group(2)), int(m.group(1)), m.group(3), m.group(5), m.group(6)+':'+m.group(7)))
ev = [e for e in ev if t0 <= e[0] <= t1]
# running[cpu] = comm; compute idle per state of render thread
running = {0: None, 1: None}
render_state = "?"
last = t0
acc = collections.Counter(); other = collections.Counter()
for t, cpu, prev, pstate, nxt in ev:
    dt = t - last
    comms = [running[c] for c in (0, 1)]
    idle = sum(1 for c in comms if c is None or c.startswith("swapper"))
    rs = "render running" if any(c.startswith("lgh-render-0") for c in comms if c) else "render off"
    acc[(idle, rs)] += dt
    if idle == 1:
        busy = [c for c in comms if c and not c.startswith("swapper")][0]
        other[busy] += dt
    last = t
    running[cpu] = nxt
tot = t1 - t0
for k, v in sorted(acc.items()): print(k, f"{100*v/tot:.1f}%")
print("one idle cpu, the other running:")
for k, v in other.most_common(12): print(f"  {k:24s} {100*v/tot:.1f}%")
