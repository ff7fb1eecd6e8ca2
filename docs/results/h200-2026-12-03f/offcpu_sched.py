# Where the render thread waits off its CPU during two cold batches, with how long. Two perf
# sessions side by side: the render thread's own switches off its CPU, with its user stack
# (-t: recorded in its context), and, machine-wide without stacks (light enough to lose nothing),
# every switch that gives it a CPU back; each sleep lasts from the one to the next of the other.
# python3 offcpu_sched.py LGHD ASSETS_DIR [LGHD FLAGS...]; the summary on stdout and
# $OUT/offcpu_sched.txt.gz (timehist's lines). LGHD should have its symbols.
import collections, gzip, importlib.machinery, importlib.util, os, re, subprocess, sys, time
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec)
loader.exec_module(bt)
perf = [os.environ.get("PERF", "/tmp/p/bin/perf")]
env = dict(os.environ, LD_LIBRARY_PATH=os.environ.get("PERF_LIBS", "/tmp/p/lib"))
binary, assets = sys.argv[1], sys.argv[2]
d = bt.Daemon(binary, assets, ["--scene-cache-mb", "0", *sys.argv[3:]])
try:
    ok, failed = bt.renderable(d, bt.find_assets(assets), 256)
    batch = ok * int(os.environ.get("COPIES", "10"))  # the eighteenth session ran COPIES=1
    d.thumbnails(batch, 256)
    pid = d.process.pid
    tid = [t for t in os.listdir(f"/proc/{pid}/task")
           if open(f"/proc/{pid}/task/{t}/comm").read().strip() == "lgh-render-0"][0]
    rec = subprocess.Popen(perf + ["record", "-q", "-o", "/tmp/off.data", "-e", "sched:sched_switch",
                                   "-t", tid, "-m", "2048", "--call-graph", "dwarf,8192"], env=env,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    rec_on = subprocess.Popen(perf + ["record", "-q", "-a", "-o", "/tmp/on.data", "-e",
                                      "sched:sched_switch", "--filter", f"next_pid == {tid}",
                                      "-m", "1024"], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(1.0)
    start = time.perf_counter()
    for _ in range(int(os.environ.get("BATCHES", "2"))):  # and BATCHES=20
        d.thumbnails(batch, 256)
    wall = time.perf_counter() - start
    time.sleep(0.2)
    rec.send_signal(2); rec_on.send_signal(2); rec.wait(); rec_on.wait()
finally:
    d.stop()
n = int(os.environ.get("BATCHES", "2")) * len(batch)
# Pass 1, without stacks: every switch, for the moments the render thread got a CPU back.
plain = subprocess.run(perf + ["script", "-i", "/tmp/on.data", "-G"], env=env,
                       capture_output=True, text=True).stdout
switch = re.compile(r"([\d.]+):\s+sched:sched_switch: .*prev_pid=(\d+) .*prev_state=(\S+) ==> .*next_pid=(\d+)")
back_on = []
for line in plain.splitlines():
    m = switch.search(line)
    if m and m.group(4) == tid:
        back_on.append(float(m.group(1)))
# Pass 2: the render thread's own events, with its user stack when it went off.
own = subprocess.run(perf + ["script", "-i", "/tmp/off.data"], env=env,
                     capture_output=True, text=True).stdout
with gzip.open(os.path.join(os.environ.get("OUT", "/tmp"), "offcpu_sched.txt.gz"), "wt") as f:
    f.write(own)
offs, cur = [], None
for line in own.splitlines():
    m = switch.search(line)
    if m:
        cur = None
        if m.group(2) == tid:
            cur = [float(m.group(1)), m.group(3), []]
            offs.append(cur)
        continue
    fr = re.match(r"\s+[0-9a-f]+\s+(.*?)\s+\((.*)\)\s*$", line)
    if fr and cur is not None:
        cur[2].append((re.sub(r"\+0x[0-9a-f]+$", "", fr.group(1)), fr.group(2)))
import bisect
waits = collections.Counter(); counts = collections.Counter(); total = 0.0; preempted = 0.0
for when, state, frames in offs:
    i = bisect.bisect_right(back_on, when)
    if i == len(back_on):
        continue
    ms = (back_on[i] - when) * 1000
    if ms > 100:  # idle between batches, not part of them
        continue
    if state.startswith("R"):
        preempted += ms
        continue
    user = [f for f in frames if "kernel" not in f[1]]
    leaf = user[0][0] if user else "?"
    lib = user[0][1].rsplit("/", 1)[-1] if user else "?"
    mine = [re.sub(r"\(.*", "", f[0])[:60] for f in user if "lgh" in f[0]][:3]
    key = f"{leaf} [{lib}] < " + " < ".join(mine)
    waits[key] += ms; counts[key] += 1; total += ms
print(f"{n} thumbnails in {wall:.3f} s ({n / wall:.0f}/s, perf running); render thread {tid}: "
      f"{len(offs)} switches off, {len(back_on)} back on; per thumbnail: slept {total / n:.3f} ms, "
      f"preempted {preempted / n:.3f} ms (sleeps over 100 ms left out: between batches)")
for k, v in waits.most_common(20):
    print(f"  {v / n:7.3f} ms  {counts[k] / n:6.2f}x  {k[:170]}")
