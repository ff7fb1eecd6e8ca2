# The two large assets of docs/DAEMON.md's parser cost table: a 1M-triangle grid GLB and a quad
# with a 4096x4096 PNG (GLB). python3 make_big_assets.py writes /tmp/big/grid1m.glb and png4096.glb.
import os; os.makedirs('/tmp/big', exist_ok=True)
import json, struct, zlib, array, sys
def glb(gltf, bin_):
    j = json.dumps(gltf).encode(); j += b' ' * ((4 - len(j) % 4) % 4)
    bin_ += b'\0' * ((4 - len(bin_) % 4) % 4)
    total = 12 + 8 + len(j) + 8 + len(bin_)
    return struct.pack('<III', 0x46546C67, 2, total) + struct.pack('<II', len(j), 0x4E4F534A) + j + struct.pack('<II', len(bin_), 0x004E4942) + bin_
# grid: n x n quads
n = 707
pos = array.array('f'); nor = array.array('f'); uv = array.array('f'); idx = array.array('I')
for y in range(n + 1):
    for x in range(n + 1):
        pos.extend((x / n - 0.5, 0.0, y / n - 0.5)); nor.extend((0, 1, 0)); uv.extend((x / n, y / n))
for y in range(n):
    for x in range(n):
        a = y * (n + 1) + x; b = a + 1; c = a + n + 1; d = c + 1
        idx.extend((a, c, b, b, c, d))
bp, bn, bu, bi = pos.tobytes(), nor.tobytes(), uv.tobytes(), idx.tobytes()
bin_ = bp + bn + bu + bi
nv = (n + 1) ** 2
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3}]}],
     "buffers": [{"byteLength": len(bin_)}],
     "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(bp)},
                     {"buffer": 0, "byteOffset": len(bp), "byteLength": len(bn)},
                     {"buffer": 0, "byteOffset": len(bp) + len(bn), "byteLength": len(bu)},
                     {"buffer": 0, "byteOffset": len(bp) + len(bn) + len(bu), "byteLength": len(bi)}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": nv, "type": "VEC3", "min": [-0.5, 0, -0.5], "max": [0.5, 0, 0.5]},
                   {"bufferView": 1, "componentType": 5126, "count": nv, "type": "VEC3"},
                   {"bufferView": 2, "componentType": 5126, "count": nv, "type": "VEC2"},
                   {"bufferView": 3, "componentType": 5125, "count": len(idx), "type": "SCALAR"}]}
open('/tmp/big/grid1m.glb', 'wb').write(glb(g, bin_))
# 4096 PNG on a quad
w = 4096
row = bytes(range(256)) * (w * 4 // 256)
raw = b''.join(b'\0' + row for _ in range(w))
def chunk(t, d): return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d) & 0xffffffff)
png = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, w, 8, 6, 0, 0, 0)) + chunk(b'IDAT', zlib.compress(raw, 1)) + chunk(b'IEND', b'')
qp = array.array('f', [-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0]).tobytes(); qu = array.array('f', [0, 1, 1, 1, 1, 0, 0, 0]).tobytes(); qi = array.array('H', [0, 1, 2, 0, 2, 3]).tobytes()
qi += b'\0\0'
bin_ = qp + qu + qi + png
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0}]}],
     "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
     "textures": [{"source": 0}], "images": [{"bufferView": 3, "mimeType": "image/png"}],
     "buffers": [{"byteLength": len(bin_)}],
     "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(qp)},
                     {"buffer": 0, "byteOffset": len(qp), "byteLength": len(qu)},
                     {"buffer": 0, "byteOffset": len(qp) + len(qu), "byteLength": 12},
                     {"buffer": 0, "byteOffset": len(qp) + len(qu) + len(qi), "byteLength": len(png)}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
                   {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
                   {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}]}
open('/tmp/big/png4096.glb', 'wb').write(glb(g, bin_))
