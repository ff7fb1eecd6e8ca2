# Poor man's profiler of lghd's render thread (fifteenth session): 40 gdb stack samples while
# warm batches of the small assets run; python3 stacks.py LGHD [LGHD FLAGS]. Counts the stacks.
import importlib.machinery, importlib.util, sys, time, subprocess, threading, os, collections
loader = importlib.machinery.SourceFileLoader("bt", "scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec); loader.exec_module(bt)
d = bt.Daemon(sys.argv[1], '/usr/share/assimp/models/glTF2', sys.argv[2:])
stop = False
def drive(batch):
    while not stop: d.thumbnails(batch, 256)
try:
    ok, failed = bt.renderable(d, bt.find_assets('/usr/share/assimp/models/glTF2'), 256)
    small = [a for a in ok if 'Engine' not in a and 'ClearCoat' not in a]
    d.thumbnails(small, 256)
    th = threading.Thread(target=drive, args=(small*3,)); th.start()
    pid = d.process.pid
    tid = [t for t in os.listdir(f'/proc/{pid}/task') if open(f'/proc/{pid}/task/{t}/comm').read().strip() == 'lgh-render-0'][0]
    stacks = collections.Counter()
    for i in range(40):
        out = subprocess.run(['gdb', '-p', tid, '-batch', '-ex', 'bt 25'], capture_output=True, text=True).stdout
        frames = [l.split(' in ')[-1].split(' (')[0] if ' in ' in l else l.split(' ')[2] for l in out.splitlines() if l.startswith('#')]
        stacks[' <- '.join(f[:60] for f in frames[:14])] += 1
        time.sleep(0.05)
    stop = True; th.join()
    for s, n in stacks.most_common(30): print(n, s, '\n')
finally:
    stop = True
    d.stop()
