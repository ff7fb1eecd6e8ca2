# The VM's CPU by thread in a cold run: perf samples lghd (all its threads) over three batches of
# the renderable assimp assets three times over, after a warm-up batch.
# python3 profile_by_thread.py LGHD ASSETS_DIR; then perf report -i /tmp/vm.data --sort pid.
import importlib.machinery, importlib.util, os, sys, time, subprocess
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec)
loader.exec_module(bt)
binary, assets = sys.argv[1], sys.argv[2]
d = bt.Daemon(binary, assets, ["--scene-cache-mb", "0"])
try:
    ok, failed = bt.renderable(d, bt.find_assets(assets), 256)
    batch = ok * 3
    d.thumbnails(batch, 256)
    rec = subprocess.Popen(["perf", "record", "-q", "-F", "2000", "-g", "-o", "/tmp/vm.data", "-p", str(d.process.pid)],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(0.5)
    t = time.perf_counter()
    for _ in range(3): d.thumbnails(batch, 256)
    print(len(batch) * 3 / (time.perf_counter() - t), "/s")
    rec.send_signal(2); rec.wait()
finally:
    d.stop()
