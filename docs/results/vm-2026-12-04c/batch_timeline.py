# When each NDJSON line of a cold batch arrives (the first thumbnail's latency, the gaps):
# python3 batch_timeline.py LGHD
import importlib.machinery, importlib.util, sys, time, json, http.client
loader = importlib.machinery.SourceFileLoader("bt", "/work/main/scripts/bench-thumbnails")
spec = importlib.util.spec_from_loader("bt", loader); bt = importlib.util.module_from_spec(spec); loader.exec_module(bt)
d = bt.Daemon(sys.argv[1], '/usr/share/assimp/models/glTF2', ["--scene-cache-mb","0"])
try:
    ok, failed = bt.renderable(d, bt.find_assets('/usr/share/assimp/models/glTF2'), 256)
    for _ in range(2): d.thumbnails(ok, 256)
    for rep in range(3):
        body = json.dumps({"assets": ok, "width": 256, "height": 256, "format": "ndjson", "settings": bt.Daemon.settings})
        c = http.client.HTTPConnection("127.0.0.1", d.port)
        t0 = time.perf_counter()
        c.request("POST", "/v1/thumbnails", body, {"Content-Type": "application/json"})
        r = c.getresponse(); times=[]
        while True:
            line = r.readline()
            if not line: break
            times.append(time.perf_counter()-t0)
        total=time.perf_counter()-t0
        gaps=[round(1000*(b-a),1) for a,b in zip([0]+times, times)]
        print(f"total {1000*total:.1f} ms first line {1000*times[0]:.1f} last {1000*times[-2]:.1f}; gaps {gaps[:6]} ... {gaps[-4:]}")
        c.close()
finally:
    d.stop()
