# The context switches from START for DURATION seconds, threads renamed by TID=NAME pairs:
#   perf script -i SCHED.data | python3 switches.py START DURATION 1234=RENDER 1240=VK_A ...
import sys, re
names = {}
ev = []
for line in sys.stdin:
    if 'sched:sched_switch' not in line: continue
    m = re.search(r'\[(\d+)\]\s+([\d.]+):.*prev_comm=(.*?) prev_pid=(\d+) prev_prio=\d+ prev_state=(\S+) ==> next_comm=(.*?) next_pid=(\d+)', line)
    if m: ev.append((float(m.group(2)), int(m.group(1)), m.group(3)+':'+m.group(4), m.group(5), m.group(6)+':'+m.group(7)))
ev.sort()
start = float(sys.argv[1]); dur = float(sys.argv[2])
lab = dict(a.split('=') for a in sys.argv[3:])
def L(x):
    pid = x.split(':')[-1]
    return lab.get(pid, x)
for t, cpu, prev, st, nxt in ev:
    if start <= t <= start + dur:
        print(f"{(t-start)*1000:8.3f} cpu{cpu} {L(prev):>12s}({st}) -> {L(nxt)}")
