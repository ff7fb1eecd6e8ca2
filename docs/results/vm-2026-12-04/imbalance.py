# Per-dispatch balance of a CPU driver's compute thread pool (fourteenth session): from
#   perf record -F 20000 -a -o P.data -- lgh-render MODEL -o x.png --repeat 200 -q
#   perf script -i P.data -F comm,tid,time,ip,dso -G > P.txt; python3 imbalance.py P.txt
# POOLS below holds the thread ids of the two pools (GL's llvmpipe and lavapipe) of that run:
# the pairs of unnamed threads that run JIT code (perf script shows them).
import sys, collections
POOLS = pools = {'gl': (11935, 11936), 'vk': (11943, 11944)}
period = 1/20000
samples = collections.defaultdict(list)
for line in open(sys.argv[1]):
    f = line.split()
    if len(f) < 5 or 'perf-' not in line: continue
    tid = int(f[1]); t = float(f[2].rstrip(':')); region = f[3][:8]
    samples[tid].append((t, region))
for name, tids in pools.items():
    ev = sorted([(t, tid, r) for tid in tids for (t, r) in samples[tid]])
    disp = []; cur = None
    for t, tid, r in ev:
        if cur and r == cur['r'] and t - cur['last'] < 0.0004:
            cur['last'] = t
        else:
            cur = {'r': r, 'first': t, 'last': t, 'span': {}}; disp.append(cur)
        s = cur['span'].setdefault(tid, [t, t, 0]); s[1] = t; s[2] += 1
    byr = collections.defaultdict(lambda: [0, 0.0, 0.0, 0.0])
    for d in disp:
        wall = d['last'] - d['first'] + period
        busy = sum(v[2] for v in d['span'].values()) * period
        ends = [v[1] for v in d['span'].values()]
        b = byr[d['r']]; b[0] += 1; b[1] += wall; b[2] += busy
        b[3] += (max(ends) - min(ends)) if len(ends) == 2 else wall
    for r, (n, wall, busy, tail) in sorted(byr.items(), key=lambda x: -x[1][1]):
        if n < 50: continue
        print(f"{name} {r}: {n} dispatches, wall {wall*1e3/n:.3f} ms, busy {busy*1e3/n:.3f} ms, efficiency {busy/(2*wall):.2f}, end gap {tail*1e3/n:.3f} ms")
