# Reads offcpu.py's perf script output: the render thread's blocked time by where it blocked.
# python3 read_offcpu.py offcpu.txt.gz UNSTRIPPED_LGHD RENDER_TID THUMBNAILS
import collections, gzip, re, subprocess, sys
path, binary, tid, thumbnails = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
events = []  # (time, prev_pid, next_pid, prev_state, frames)
cur = None
for line in gzip.open(path, "rt"):
    m = re.match(r"\s*([\d.]+): sched:sched_switch: .*prev_pid=(\d+) .*prev_state=(\S+) ==> .*next_pid=(\d+)", line)
    if m:
        cur = [float(m.group(1)), m.group(2), m.group(4), m.group(3), []]
        events.append(cur)
        continue
    f = re.match(r"\s+([0-9a-f]+)\s+(.*?)\s+\((.*)\)\s*$", line)
    if f and cur is not None:
        cur[4].append((int(f.group(1), 16), f.group(2), f.group(3)))
addrs = sorted({a for e in events for a, sym, dso in e[4] if dso.endswith("/lghd") and sym.startswith("[unknown")})
names = {}
if addrs:
    out = subprocess.run(["addr2line", "-f", "-C", "-e", binary] + [hex(a) for a in addrs],
                         capture_output=True, text=True).stdout.splitlines()
    names = {a: out[2 * i] for i, a in enumerate(addrs)}
def name(a, sym, dso):
    s = names.get(a, sym) if dso.endswith("/lghd") else sym
    return re.sub(r"\(.*", "", s)[:60]
blocked = collections.Counter(); count = collections.Counter(); total = 0.0; runnable = 0.0
for i, e in enumerate(events):
    if e[1] != tid:
        continue
    back = next((x for x in events[i + 1:] if x[2] == tid), None)
    if back is None:
        continue
    ms = (back[0] - e[0]) * 1000
    if e[3].startswith("R"):  # preempted: waiting for a CPU, not blocked
        runnable += ms
        continue
    user = [fr for fr in e[4] if "kernel" not in fr[2]]
    prim = name(*user[0]) if user else "?"
    own = [name(*fr) for fr in user if fr[2].endswith("/lghd")][:3]
    key = f"{prim} < " + " < ".join(own)
    blocked[key] += ms; count[key] += 1; total += ms
outs = sum(1 for e in events if e[1] == tid)
ins = sum(1 for e in events if e[2] == tid)
print(f"{outs} switches off the CPU, {ins} back on: the times below hold only when they match")
print(f"blocked {total / thumbnails:.3f} ms per thumbnail, preempted {runnable / thumbnails:.3f} ms")
print("   ms   sleeps per thumbnail, where (leaf < lghd callers)")
for k, v in blocked.most_common(15):
    print(f"  {v / thumbnails:7.3f} ms  {count[k] / thumbnails:6.2f}x  {k}")
