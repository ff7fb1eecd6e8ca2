# Where the render thread waits off its CPU during cold batches: every sched_switch that takes
# lgh-render-0 off its CPU (with its user stack) and the switch that brings it back, system-wide
# with a filter on its thread id; blocked time summed by the stack's nearest lghd functions.
# python3 offcpu.py LGHD ASSETS_DIR [LGHD FLAGS...]; writes $OUT/offcpu.txt.gz (perf script).
import gzip, importlib.machinery, importlib.util, os, subprocess, sys, time
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec)
loader.exec_module(bt)
perf = [os.environ.get("PERF", "/tmp/p/bin/perf")]
env = dict(os.environ, LD_LIBRARY_PATH=os.environ.get("PERF_LIBS", "/tmp/p/lib"))
binary, assets = sys.argv[1], sys.argv[2]
d = bt.Daemon(binary, assets, ["--scene-cache-mb", "0", *sys.argv[3:]])
try:
    ok, failed = bt.renderable(d, bt.find_assets(assets), 256)
    batch = ok * 10
    d.thumbnails(batch, 256)
    pid = d.process.pid
    tid = [t for t in os.listdir(f"/proc/{pid}/task")
           if open(f"/proc/{pid}/task/{t}/comm").read().strip() == "lgh-render-0"][0]
    def stat():
        run, wait, slices = open(f"/proc/{pid}/task/{tid}/schedstat").read().split()
        return int(run), int(wait)
    rec = subprocess.Popen(perf + ["record", "-q", "-a", "-o", "/tmp/offcpu.data", "-e",
                                   "sched:sched_switch", "--filter",
                                   f"prev_pid == {tid} || next_pid == {tid}",
                                   "--call-graph", "dwarf,8192", "-m", "1024"], env=env)
    time.sleep(1.0)
    run0, wait0 = stat(); start = time.perf_counter()
    for _ in range(2):
        d.thumbnails(batch, 256)
    wall = time.perf_counter() - start; run1, wait1 = stat()
    rec.send_signal(2); rec.wait()
    n = 2 * len(batch)
    print(f"{n} thumbnails in {wall:.3f} s; render thread per thumbnail: on CPU "
          f"{(run1 - run0) / 1e6 / n:.3f} ms, waiting for a CPU {(wait1 - wait0) / 1e6 / n:.3f} ms, "
          f"wall {wall * 1000 / n:.3f} ms", flush=True)
finally:
    d.stop()
out = subprocess.run(perf + ["script", "-i", "/tmp/offcpu.data", "-F", "time,event,trace,ip,sym,dso"],
                     env=env, capture_output=True, text=True).stdout
with gzip.open(os.path.join(os.environ.get("OUT", "/tmp"), "offcpu.txt.gz"), "wt") as f:
    f.write(out)
print("render tid", tid, "script lines", out.count("\n"))
