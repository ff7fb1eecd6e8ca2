# Which thread ran on each CPU, 0.2 ms a character, 80 ms from START (fifteenth session):
#   perf script -i SCHED.data | python3 timeline.py [START]
# (SCHED.data from `perf sched record`; sched_record.py records one for lghd's warm batches).
# It prints each thread's time per CPU, then the timeline and the letters' legend.
import sys, re, collections
# segments per cpu from sched_switch
ev = []
for line in sys.stdin:
    if 'sched:sched_switch' not in line: continue
    m = re.search(r'\[(\d+)\]\s+([\d.]+):.*next_comm=(.*?) next_pid=(\d+)', line)
    if m: ev.append((float(m.group(2)), int(m.group(1)), m.group(3), int(m.group(4))))
ev.sort()
names = {}
def cls(comm, pid):
    return comm + ':' + str(pid)
cur = {}
seg = collections.defaultdict(list)
for t, cpu, comm, pid in ev:
    if cpu in cur:
        seg[cpu].append((cur[cpu][0], t, cur[cpu][1]))
    cur[cpu] = (t, cls(comm, pid))
t0 = ev[0][0]; t1 = ev[-1][0]
tot = collections.Counter()
for cpu, ss in seg.items():
    for a, b, who in ss: tot[(cpu, who)] += b - a
for (cpu, who), v in sorted(tot.items(), key=lambda x: -x[1])[:30]:
    print(cpu, who, round(v*1000, 1))
print('window', round((t1 - t0) * 1000, 1))
# ascii timeline
legend = {}
def sym(who):
    if who.startswith('swapper'): return '.'
    if who not in legend: legend[who] = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz'[len(legend) % 52]
    return legend[who]
start = float(sys.argv[1]) if len(sys.argv) > 1 else t0 + (t1 - t0) / 2
slot = 0.0002
for cpu in sorted(seg):
    line = ''
    for k in range(400):
        a = start + k * slot; b = a + slot
        occ = collections.Counter()
        for s, e, who in seg[cpu]:
            if e > a and s < b: occ[who] += min(e, b) - max(s, a)
        line += sym(occ.most_common(1)[0][0]) if occ else ' '
    print('cpu', cpu)
    for i in range(0, 400, 100): print('  ', line[i:i+100])
print(legend)
