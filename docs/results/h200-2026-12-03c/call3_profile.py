# Cold thumbnails through one lghd (scene cache off, 31 assets x 10 copies per batch), profiled
# with perf: the render thread (lgh-render-0) with DWARF call graphs, and the whole process
# without, each over three batches after a warm-up batch.
import importlib.machinery, importlib.util, os, subprocess, sys, time
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec)
loader.exec_module(bt)
perf = [os.path.abspath(".devbundle-p/bin/perf")]
env = dict(os.environ, LD_LIBRARY_PATH=os.path.abspath(".devbundle-p/lib"))
d = bt.Daemon(os.environ.get("LGHD_BIN", ".devbundle/bin/lghd"), ".assets",
              ["--scene-cache-mb", "0"] + os.environ.get("LGHD_FLAGS", "--require-gpu").split())
try:
    ok, failed = bt.renderable(d, bt.find_assets(".assets"), 256)
    batch = ok * int(os.environ.get("COPIES", "10"))
    d.thumbnails(batch, 256)
    pid = d.process.pid
    render = [t for t in os.listdir(f"/proc/{pid}/task")
              if open(f"/proc/{pid}/task/{t}/comm").read().strip() == "lgh-render-0"]
    print("assets", len(ok), "render thread", render, flush=True)
    for name, args in (("render", ["-t", render[0], "-F", "1999", "-m", "1024", "--call-graph", "dwarf,12288"]),
                       ("process", ["-p", str(pid), "-F", "999"])):
        rec = subprocess.Popen(perf + ["record", "-o", f"/tmp/{name}.data"] + args, env=env)
        time.sleep(1.0)
        start = time.perf_counter()
        for _ in range(3):
            d.thumbnails(batch, 256)
        print(name, "3 batches of", len(batch), "in", round(time.perf_counter() - start, 3), "s",
              flush=True)
        rec.send_signal(2)
        rec.wait()
finally:
    d.stop()
