# Where the 2-core VM's CPUs sit idle during a cold batch, by what lghd's render thread waits for
# at the time: sched_switch machine-wide (no stacks) and the render thread's own switches with DWARF
# stacks. python3 idle_by_render_wait.py LGHD ASSETS_DIR (LGHD with its symbols: a lean build's
# unstripped lghd), run from the repository root.
# Who leaves a CPU idle: sched_switch system-wide during cold batches; for each switch to idle,
# the task that slept (with its stack) weighted by how long the CPU then stayed idle.
import importlib.machinery, importlib.util, os, re, subprocess, sys, time, collections
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec)
loader.exec_module(bt)
binary, assets = sys.argv[1], sys.argv[2]
d = bt.Daemon(binary, assets, ["--scene-cache-mb", "0"])
try:
    ok, failed = bt.renderable(d, bt.find_assets(assets), 256)
    batch = ok * 6
    d.thumbnails(batch, 256)
    rec = subprocess.Popen(["perf", "record", "-q", "-a", "-e", "sched:sched_switch", "-o", "/tmp/idle.data"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    pid = d.process.pid
    tid = [t for t in os.listdir(f"/proc/{pid}/task") if open(f"/proc/{pid}/task/{t}/comm").read().strip() == "lgh-render-0"][0]
    rec2 = subprocess.Popen(["perf", "record", "-q", "-e", "sched:sched_switch", "-t", tid, "--call-graph", "dwarf,16384", "-m", "1024", "-o", "/tmp/render.data"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(0.5)
    t = time.perf_counter(); d.thumbnails(batch, 256); wall = time.perf_counter() - t
    rec.send_signal(2); rec.wait(); rec2.send_signal(2); rec2.wait()
finally:
    d.stop()
print(f"{len(batch)} thumbnails in {wall:.2f}s")
out = subprocess.run(["perf", "script", "-i", "/tmp/idle.data", "-F", "comm,tid,cpu,time,trace,ip,sym,dso"],
                     capture_output=True, text=True).stdout
events = []
for block in out.splitlines():
    lines = [block]
    if not lines: continue
    m = re.match(r"\s*(\S.*?)\s+(\d+)\s+\[(\d+)\]\s+([\d.]+):\s+(.*)", lines[0])
    if not m: continue
    comm, tid, cpu, ts, trace = m.groups()
    nm = re.search(r"next_comm=(.*?) next_pid=(\d+)", trace)
    pm = re.search(r"prev_comm=(.*?) prev_pid=(\d+)", trace)
    stack = [l.split(None, 1)[1] if len(l.split(None,1))>1 else l for l in lines[1:]]
    events.append((float(ts), int(cpu), pm.group(1) if pm else comm, int(pm.group(2)) if pm else 0, nm.group(1), int(nm.group(2)), stack))
events.sort()
rout = subprocess.run(["perf", "script", "-i", "/tmp/render.data", "-F", "tid,time,ip,sym,dso"], capture_output=True, text=True).stdout
render_stacks = {}
for block in rout.split("\n\n"):
    lines = block.strip().splitlines()
    if not lines: continue
    m = re.match(r"\s*(\d+)\s+([\d.]+):", lines[0])
    if not m: continue
    fr = []
    for l in lines[1:]:
        p = l.split(None, 1)
        if len(p) < 2 or "kernel" in p[1]: continue
        name = p[1].split(" (")[0].strip()
        if name == "[unknown]": continue
        fr.append(name[:45])
    render_stacks[round(float(m.group(2)), 6)] = " < ".join(fr[:7])
idle_since = {}
blame = collections.Counter(); blame_comm = collections.Counter(); total_idle = 0.0
t0, t1 = events[0][0], events[-1][0]
for ts, cpu, pcomm, ppid, ncomm, npid, stack in events:
    if npid == 0:
        # user frames that name the wait: first frame outside the kernel
        frames = [f for f in stack if "kernel" not in f and "unknown" not in f][:4]
        idle_since[cpu] = (ts, pcomm, " < ".join(x.split("(")[0].strip()[:60] for x in frames))
    elif cpu in idle_since:
        start, who, why = idle_since.pop(cpu)
        dur = ts - start
        total_idle += dur
        blame[(who, why)] += dur; blame_comm[who] += dur
print(f"span {t1-t0:.2f}s, idle {total_idle:.2f} cpu-s ({100*total_idle/(2*(t1-t0)):.0f}% of 2 CPUs)")
for k, v in blame_comm.most_common(10): print(f"  {v*1000:8.1f} ms  {k}")
print("by stack:")
for (who, why), v in blame.most_common(25): print(f"  {v*1000:8.1f} ms  {who:16s} {why}")
# Render thread state during idle time
render = None
for ev in events:
    if ev[2].startswith("lgh-render"): render = ev[3]; break
import bisect
rkeys = sorted(render_stacks)
state = ("unknown", "")  # render thread state
idle_cpus = {}
rts = [e[0] for e in events if e[3] == render or e[5] == render]
w0, w1 = rts[0] + 0.15, rts[-1] - 0.15
print(f"window {w1-w0:.2f}s")
by_state = collections.Counter()
last_ts = events[0][0]
for ts, cpu, pcomm, ppid, ncomm, npid, stack in events:
    dt = ts - last_ts
    if w0 <= ts <= w1: by_state[state] += dt * len(idle_cpus)
    last_ts = ts
    if npid == 0: idle_cpus[cpu] = True
    else: idle_cpus.pop(cpu, None)
    if ppid == render and npid != render:
        i = bisect.bisect_left(rkeys, ts)
        best = min((abs(rkeys[j] - ts), rkeys[j]) for j in (i - 1, i) if 0 <= j < len(rkeys)) if rkeys else (1, 0)
        state = ("sleeping", render_stacks[best[1]] if best[0] < 50e-6 else "?")
    if npid == render: state = ("running", "")
print("idle CPU time by the render thread's state:")
for k, v in by_state.most_common(15): print(f"  {v*1000:8.1f} ms  {k[0]} {k[1]}")
oncpu = collections.Counter(); since = {}
for ts, cpu, pcomm, ppid, ncomm, npid, stack in events:
    if ppid in since: oncpu[pcomm] += ts - since.pop(ppid)
    since[npid] = ts
print("on-CPU by comm (ms):", {k: round(v*1000) for k, v in oncpu.most_common(12)})
print("render tid", render)
