# Nineteenth session: the time one of the two cores idles, split by what the render thread was
# doing then (running, preempted, or the lgh:: frames of the wait it slept in) and by the thread
# the busy core ran. python3 idle_by_wait.py LGHD [LGHD FLAGS], BATCHES=10 by default, from the
# repository root (perf needs root or perf_event_paranoid <= 1).
import collections, importlib.machinery, importlib.util, os, re, subprocess, sys, time, bisect
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec)
loader.exec_module(bt)
binary, assets = sys.argv[1], "/usr/share/assimp/models/glTF2"
d = bt.Daemon(binary, assets, ["--scene-cache-mb", "0", *sys.argv[2:]])
try:
    ok, failed = bt.renderable(d, bt.find_assets(assets), 256)
    batch = ok
    d.thumbnails(batch, 256)
    pid = d.process.pid
    tid = [t for t in os.listdir(f"/proc/{pid}/task")
           if open(f"/proc/{pid}/task/{t}/comm").read().strip() == "lgh-render-0"][0]
    names = {}
    for p in [pid] + subprocess.run(["pgrep", "-P", str(pid)], capture_output=True, text=True).stdout.split():
        for t in os.listdir(f"/proc/{p}/task"):
            names[t] = open(f"/proc/{p}/task/{t}/comm").read().strip() + (":parser" if str(p) != str(pid) else "") + ":" + t
    rec = subprocess.Popen(["perf", "record", "-q", "-o", "/tmp/off.data", "-e", "sched:sched_switch",
                            "-t", tid, "-m", "2048", "--call-graph", "dwarf,8192"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    rec_all = subprocess.Popen(["perf", "record", "-q", "-a", "-o", "/tmp/all_sw.data", "-e", "sched:sched_switch", "-m", "4096"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(1.0)
    t0 = time.clock_gettime(time.CLOCK_MONOTONIC)
    B = int(os.environ.get("BATCHES", "10"))
    for _ in range(B): d.thumbnails(batch, 256)
    t1 = time.clock_gettime(time.CLOCK_MONOTONIC)
    time.sleep(0.2)
    rec.send_signal(2); rec_all.send_signal(2); rec.wait(); rec_all.wait()
finally:
    d.stop()
print(f"{B*len(batch)/(t1-t0):.1f}/s"); print(sorted(names.items(), key=lambda kv: int(kv[0])))
switch = re.compile(r"\[(\d+)\]\s+([\d.]+):\s+sched:sched_switch: .*prev_pid=(\d+) .*prev_state=(\S+) ==> .*next_pid=(\d+)")
allev = []
for line in subprocess.run(["perf", "script", "-i", "/tmp/all_sw.data", "-F", "cpu,time,trace"], capture_output=True, text=True).stdout.splitlines():
    m = re.search(r"\[(\d+)\]\s+([\d.]+):\s+prev_comm=.*prev_pid=(\d+) .*prev_state=(\S+) ==> next_comm=.*next_pid=(\d+)", line)
    if m: allev.append((float(m.group(2)), int(m.group(1)), m.group(3), m.group(5)))
allev.sort()
own = subprocess.run(["perf", "script", "-i", "/tmp/off.data"], capture_output=True, text=True).stdout
sw2 = re.compile(r"([\d.]+):\s+sched:sched_switch: .*prev_pid=(\d+) .*prev_state=(\S+) ==> .*next_pid=(\d+)")
offs, cur = [], None
for line in own.splitlines():
    m = sw2.search(line)
    if m:
        cur = None
        if m.group(2) == tid:
            cur = [float(m.group(1)), m.group(3), []]; offs.append(cur)
        continue
    fr = re.match(r"\s+[0-9a-f]+\s+(.*?)\s+\((.*)\)\s*$", line)
    if fr and cur is not None: cur[2].append(re.sub(r"\+0x[0-9a-f]+$", "", fr.group(1)))
def cat(state, frames):
    if state.startswith("R"): return "preempted"
    mine = [re.sub(r"\(.*", "", f) for f in frames if "lgh" in f]
    return " < ".join(m.replace("lgh::", "")[:45] for m in mine[:2]) or "?"
offt = [o[0] for o in offs]
# render-thread state at time t: find last own off event <= t and whether back on since.
back_on = [e[0] for e in allev if e[3] == tid]
def rstate(t):
    i = bisect.bisect_right(offt, t) - 1
    if i < 0: return "running"
    j = bisect.bisect_right(back_on, offs[i][0])
    if j < len(back_on) and back_on[j] <= t: return "running"
    return cat(offs[i][1], offs[i][2])
curpid = {}
acc = collections.Counter(); whoacc = collections.Counter()
start = allev[0][0]
lo, hi = start + 1.0 - 0.0, allev[-1][0] - 0.2
prev = None
for ev in allev:
    t = ev[0]
    if prev is not None and lo <= prev <= hi:
        dt = t - prev
        idle = [c for c in (0, 1) if curpid.get(c, "0") == "0"]
        if len(idle) == 1:
            other = curpid.get(1 - idle[0], "0")
            st = rstate(prev)
            acc[st] += dt
            whoacc[(st, names.get(other, other))] += dt
        acc["_total"] += dt
        acc[f"_idle{len(idle)}"] += dt
    curpid[ev[1]] = ev[3]
    prev = t
tot = acc["_total"]
print({k: round(100*v/tot, 1) for k, v in acc.items() if k.startswith("_idle")})
for k, v in acc.most_common(14):
    if not k.startswith("_"): print(f"  {100*v/tot:5.1f}%  {k}")
print("by (render state, thread on the busy core):")
for (st, who), v in whoacc.most_common(25):
    print(f"  {100*v/tot:5.1f}%  {st:60s} {who}")
