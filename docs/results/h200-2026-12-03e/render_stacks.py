# The cold render thread's call stacks (DWARF) for reading off-device: perf script output with
# dso-relative addresses, gzipped into $OUT/<label>_stacks.txt.gz.
import gzip, importlib.machinery, importlib.util, os, subprocess, sys, time
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec)
loader.exec_module(bt)
perf = ["/tmp/p/bin/perf"]
env = dict(os.environ, LD_LIBRARY_PATH="/tmp/p/lib")
label = sys.argv[1]
d = bt.Daemon(os.environ.get("LGHD_BIN", ".devbundle/bin/lghd"), ".assets",
              ["--scene-cache-mb", "0", "--require-gpu"])
try:
    ok, failed = bt.renderable(d, bt.find_assets(".assets"), 256)
    batch = ok * 10
    d.thumbnails(batch, 256)
    pid = d.process.pid
    render = [t for t in os.listdir(f"/proc/{pid}/task")
              if open(f"/proc/{pid}/task/{t}/comm").read().strip() == "lgh-render-0"]
    rec = subprocess.Popen(perf + ["record", "-q", "-o", f"/tmp/{label}_r.data", "-t", render[0],
                                   "-F", "2999", "-m", "1024", "--call-graph", "dwarf,16384"], env=env)
    time.sleep(1.0)
    start = time.perf_counter()
    for _ in range(2):
        d.thumbnails(batch, 256)
    print(label, "2 batches of", len(batch), "in", round(time.perf_counter() - start, 3), "s", flush=True)
    rec.send_signal(2)
    rec.wait()
finally:
    d.stop()
out = subprocess.run(perf + ["script", "-i", f"/tmp/{label}_r.data", "-F", "time,ip,sym,dso"],
                     env=env, capture_output=True, text=True).stdout
with gzip.open(os.path.join(os.environ["OUT"], f"{label}_stacks.txt.gz"), "wt") as f:
    f.write(out)
print(label, "stack lines", out.count("\n"))
