# perf sched record -a over 2.4 s of lghd's warm batches (the asset list three times over):
#   python3 sched_record.py LGHD ASSETS  -> sched.data, for timeline.py and switches.py
import importlib.machinery, importlib.util, os, sys, time, subprocess
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec)
loader.exec_module(bt)
binary, assets_root = sys.argv[1], sys.argv[2]
extra = sys.argv[3:]
d = bt.Daemon(binary, assets_root, [*extra])
try:
    ok, failed = bt.renderable(d, bt.find_assets(assets_root), 256)
    batch = ok * 3
    d.thumbnails(batch, 256)
    print("PID", d.process.pid, flush=True)
    p = subprocess.Popen(["perf","sched","record","-a","-o","sched.data","--","sleep","2.4"],stderr=subprocess.DEVNULL)
    time.sleep(0.3)
    start=time.perf_counter(); n=0
    while time.perf_counter()-start < 2.2:
        d.thumbnails(batch, 256); n+=len(batch)
    print(n/(time.perf_counter()-start), "per s", flush=True)
    p.wait()
finally:
    d.stop()
