# Samples of JIT-compiled shader code (perf script -G -F tid,ip,dso, lines of the perf-PID.map dso:
# "TID IP") grouped into code regions (gaps over 4 KB), per thread: which compiled shader the
# compute pools spend their time in (sixteenth session): python3 jit_clusters.py IPS.txt [N]
import collections, bisect, sys
by=collections.defaultdict(list)
for l in open(sys.argv[1]):
    t,ip=l.split(); by[int(t)].append(int(ip,16))
allips=sorted(set(ip for v in by.values() for ip in v))
clusters=[]; start=allips[0]; prev=allips[0]
for ip in allips[1:]:
    if ip-prev>4096: clusters.append((start,prev)); start=ip
    prev=ip
clusters.append((start,prev))
starts=[c[0] for c in clusters]
tot=collections.Counter(); hot=collections.defaultdict(collections.Counter)
for t,v in by.items():
    for ip in v:
        i=bisect.bisect_right(starts,ip)-1; tot[(i,t)]+=1; hot[i][ip]+=1
ct=collections.Counter()
for (i,t),n in tot.items(): ct[i]+=n
total=sum(ct.values())
for i,n in ct.most_common(int(sys.argv[2]) if len(sys.argv)>2 else 15):
    th={t:tot[(i,t)] for t in by if tot[(i,t)]}
    print(f'cluster {i} {hex(clusters[i][0])} size {clusters[i][1]-clusters[i][0]:6d} samples {n:5d} ({100*n/total:4.1f}%) threads {th} hot {[(hex(a),c) for a,c in hot[i].most_common(3)]}')
