import gzip, re, subprocess, sys, collections
path, binary = sys.argv[1], sys.argv[2]
samples = []; cur = None
for line in gzip.open(path, "rt"):
    if line.strip().endswith(":") and not line.startswith("\t"):
        cur = []; samples.append(cur); continue
    m = re.match(r"\s+([0-9a-f]+)\s+(.*?)\s+\((.*)\)\s*$", line)
    if m and cur is not None:
        cur.append((int(m.group(1), 16), m.group(2), m.group(3)))
addrs = sorted({a for s in samples for a, sym, dso in s if dso.endswith("/lghd")})
out = subprocess.run(["addr2line", "-f", "-C", "-e", binary] + [hex(a) for a in addrs],
                     capture_output=True, text=True).stdout.splitlines()
names = {a: re.sub(r"\(.*", "", out[2*i])[:90] for i, a in enumerate(addrs)}
def frame_name(a, sym, dso):
    if dso.endswith("/lghd"): return names.get(a, "?")
    base = dso.rsplit("/", 1)[-1]
    return f"{sym} [{base}]" if sym != "[unknown]" else f"[{base}]"
n = len(samples)
incl = collections.Counter(); leaf_dso = collections.Counter(); leaf = collections.Counter()
first_lghd = collections.Counter()
for s in samples:
    seen = set()
    for a, sym, dso in s:
        f = frame_name(a, sym, dso)
        if dso.endswith("/lghd") and f not in seen:
            incl[f] += 1; seen.add(f)
    if s:
        a, sym, dso = s[0]
        leaf_dso[dso.rsplit("/",1)[-1]] += 1
        leaf[frame_name(a, sym, dso)] += 1
        for a2, sym2, dso2 in s:
            if dso2.endswith("/lghd"):
                first_lghd[frame_name(a2, sym2, dso2)] += 1; break
print("samples", n)
print("== leaf by dso"); [print(f"{100*v/n:6.1f}%  {k}") for k, v in leaf_dso.most_common(12)]
print("== leaf functions"); [print(f"{100*v/n:6.1f}%  {k}") for k, v in leaf.most_common(25)]
print("== nearest lghd function (self incl. callees outside lghd)"); [print(f"{100*v/n:6.1f}%  {k}") for k, v in first_lghd.most_common(40)]
print("== inclusive lghd functions"); [print(f"{100*v/n:6.1f}%  {k}") for k, v in incl.most_common(70)]
