# While one CPU idles, who runs alone on the other (perf script of a perf sched record, the
# render thread's first to last switch): perf script -i SCHED.data | python3 alone.py
import sys, re, collections
ev=[]
for line in sys.stdin:
    if 'sched:sched_switch' not in line: continue
    m = re.search(r'\[(\d+)\]\s+([\d.]+):.*next_comm=(.*?) next_pid=(\d+)', line)
    if m: ev.append((float(m.group(2)), int(m.group(1)), m.group(3)+':'+m.group(4)))
ev.sort()
rt=[t for t,c,w in ev if w.startswith('lgh-render')]
w0,w1=min(rt),max(rt)
cur={}; last=None
alone=collections.Counter(); both=0; busy2=0; tot=0
for t,cpu,who in ev:
    if last is not None and len(cur)==2 and last>=w0 and t<=w1:
        dt=t-last; tot+=dt
        idle=[c for c,w in cur.items() if w.startswith('swapper')]
        if len(idle)==2: both+=dt
        elif len(idle)==1:
            other=[w for c,w in cur.items() if not w.startswith('swapper')][0]
            alone[other]+=dt
        else: busy2+=dt
    cur[cpu]=who; last=t
print(f"total {tot*1000:.0f} ms: both busy {100*busy2/tot:.1f}%, one idle {100*sum(alone.values())/tot:.1f}%, both idle {100*both/tot:.1f}%")
for w,v in alone.most_common(12): print(f"  alone {w:24s} {v*1000:7.1f} ms {100*v/tot:5.1f}%")
