# Where the VM's CPU goes in cold batches, by JIT code region and thread (fourteenth session):
#   python3 prof.py LGHD ASSETS OUT.data   (perf record -a at 1,999 Hz over three cold batches of
#   the asset list three times over), then:
#   perf script -i OUT.data -F comm,tid,time,ip,dso -G | grep perf- | awk '{print $1, $2, substr($4,1,8)}' | sort | uniq -c | sort -rn
# counts samples of llvmpipe's and lavapipe's compiled shaders by thread and 64 KiB code region;
# the order of regions within a frame (perf script's times) tells which pass each one is.
import importlib.machinery, importlib.util, os, sys, time, subprocess, signal
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec)
loader.exec_module(bt)
binary, root, out = sys.argv[1], sys.argv[2], sys.argv[3]
d = bt.Daemon(binary, root, ["--scene-cache-mb", "0", *sys.argv[4:]])
try:
    ok, failed = bt.renderable(d, bt.find_assets(root), 256)
    batch = ok * 3
    d.thumbnails(batch, 256)
    p = subprocess.Popen(["perf", "record", "-F", "1999", "-g", "-a", "-o", out], stderr=subprocess.DEVNULL)
    time.sleep(0.5)
    start = time.perf_counter()
    for _ in range(3): d.thumbnails(batch, 256)
    wall = time.perf_counter() - start
    p.send_signal(signal.SIGINT); p.wait()
    print(f"{len(batch)*3} thumbnails in {wall:.2f} s ({len(batch)*3/wall:.1f}/s)")
finally:
    d.stop()
