#!/usr/bin/env python3
"""Writes a closed test room for the build benchmarks as one .gltf file
(buffer embedded; a .glb name writes binary glTF): a 4 x 3 x 5 box room
(white floor and ceiling, red and green side walls, white back and front
walls, an emissive ceiling panel), a camera inside it looking at the back
wall, and a bumpy sphere ("blob") on the floor tessellated to about
TRIANGLES triangles in all (default 69000: the ~69k-triangle closed room of
issue 16). Nothing is read from disk; plain Python (no numpy).

The room, its materials and the glTF writer are also
perf/make-scale-scene.py's, which imports them from here.

    perf/make-room.py OUT.gltf [TRIANGLES]
"""
import base64
import json
import math
import struct
import sys

ROOM = (-2.0, 2.0, 0.0, 3.0, -5.0, 0.0)  # x0, x1, y0, y1, z0, z1

MATERIALS = [
    {"name": "white", "pbrMetallicRoughness": {"baseColorFactor": [0.73, 0.73, 0.73, 1],
                                                "metallicFactor": 0, "roughnessFactor": 1}},
    {"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.63, 0.065, 0.05, 1],
                                              "metallicFactor": 0, "roughnessFactor": 1}},
    {"name": "green", "pbrMetallicRoughness": {"baseColorFactor": [0.14, 0.45, 0.091, 1],
                                                "metallicFactor": 0, "roughnessFactor": 1}},
    {"name": "light", "emissiveFactor": [1, 1, 1],
     "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 15}},
     "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0}},
]


def quad(p0, p1, p2, p3, n):
    return [p0, p1, p2, p3], [n] * 4, [0, 1, 2, 0, 2, 3]


def room():
    """The walls and the ceiling light: [(name, (positions, normals,
    indices), material)], inward normals, counter-clockwise seen from
    inside."""
    x0, x1, y0, y1, z0, z1 = ROOM
    return [
        ("floor", quad((x0, y0, z1), (x1, y0, z1), (x1, y0, z0), (x0, y0, z0), (0, 1, 0)), 0),
        ("ceiling", quad((x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1), (0, -1, 0)), 0),
        ("back", quad((x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0), (0, 0, 1)), 0),
        ("front", quad((x1, y0, z1), (x0, y0, z1), (x0, y1, z1), (x1, y1, z1), (0, 0, -1)), 0),
        ("left", quad((x0, y0, z1), (x0, y0, z0), (x0, y1, z0), (x0, y1, z1), (1, 0, 0)), 1),
        ("right", quad((x1, y0, z0), (x1, y0, z1), (x1, y1, z1), (x1, y1, z0), (-1, 0, 0)), 2),
        ("light", quad((-0.5, y1 - 1e-3, -3.0), (0.5, y1 - 1e-3, -3.0), (0.5, y1 - 1e-3, -2.0),
                       (-0.5, y1 - 1e-3, -2.0), (0, -1, 0)), 3),
    ]


def blob(n_lat, n_lon, centre, radius):
    """UV sphere with a smooth bump field: positions, normals, indices."""
    pos, nrm, idx = [], [], []
    for i in range(n_lat + 1):
        th = math.pi * i / n_lat
        for j in range(n_lon + 1):
            ph = 2 * math.pi * j / n_lon
            d = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            r = radius * (1 + 0.08 * math.sin(5 * th) * math.cos(7 * ph)
                          + 0.04 * math.sin(11 * ph + 3 * th))
            pos.append((centre[0] + r * d[0], centre[1] + r * d[1], centre[2] + r * d[2]))
            nrm.append(d)
    row = n_lon + 1
    for i in range(n_lat):
        for j in range(n_lon):
            a, b = i * row + j, i * row + j + 1
            c, e = (i + 1) * row + j, (i + 1) * row + j + 1
            if i > 0:
                idx += [a, b, c]
            if i < n_lat - 1:
                idx += [b, e, c]
    return pos, nrm, idx


def _packed(data, width):
    """Little-endian float32 vectors of `width` (3: VEC3, 2: VEC2) or, for
    width 0, uint32 scalars of `data` (lists of tuples / ints, or numpy
    arrays): (bytes, count, min, max), the bounds those of the float32
    values (as glTF asks)."""
    if hasattr(data, "tobytes"):  # numpy
        if width:
            a = data.reshape(-1, width).astype("<f4")
            return a.tobytes(), len(a), a.min(axis=0).tolist(), a.max(axis=0).tolist()
        a = data.reshape(-1).astype("<u4")
        return a.tobytes(), len(a), None, None
    if width:
        fmt = "<%df" % width
        b = b"".join(struct.pack(fmt, *v) for v in data)
        stored = list(struct.iter_unpack(fmt, b))  # the bounds of what is stored
        return (b, len(data), [min(p[k] for p in stored) for k in range(width)],
                [max(p[k] for p in stored) for k in range(width)])
    return struct.pack("<%dI" % len(data), *data), len(data), None, None


def write_gltf(path, meshes, materials=MATERIALS, generator="DIRT perf/make-room.py",
               aspect=1.0, images=()):
    """Writes `meshes` ([(name, (positions, normals, indices[, uvs]),
    material)], lists or numpy arrays; uvs, where given and not None, become
    TEXCOORD_0), `materials` and a camera at eye height near the front wall
    looking down -z (glTF cameras look down their local -z): binary glTF
    when `path` ends in .glb, else .gltf with the buffer embedded. `images`
    (PNG bytes) are stored in the buffer as glTF images, texture k showing
    image k through one repeating, trilinear sampler, for `materials` to
    reference by index. Returns the triangle count."""
    buf = bytearray()
    views, accessors, gl_meshes, nodes = [], [], [], []
    tris = 0

    def view(b, target=None):
        while len(buf) % 4:
            buf.append(0)
        v = {"buffer": 0, "byteOffset": len(buf), "byteLength": len(b)}
        if target is not None:
            v["target"] = target
        views.append(v)
        buf.extend(b)
        return len(views) - 1

    for name, geometry, mat in meshes:
        pos, nrm, idx = geometry[:3]
        uv = geometry[3] if len(geometry) > 3 else None
        prim = {"material": mat, "mode": 4, "attributes": {}}
        for key, data, width in (("POSITION", pos, 3), ("NORMAL", nrm, 3),
                                 ("TEXCOORD_0", uv, 2), ("indices", idx, 0)):
            if data is None:
                continue
            b, count, lo, hi = _packed(data, width)
            acc = {"bufferView": view(b, 34963 if key == "indices" else 34962),
                   "count": count, "componentType": 5125 if key == "indices" else 5126,
                   "type": {3: "VEC3", 2: "VEC2", 0: "SCALAR"}[width]}
            if key == "POSITION":
                acc["min"], acc["max"] = lo, hi
            accessors.append(acc)
            if key == "indices":
                prim["indices"] = len(accessors) - 1
                tris += count // 3
            else:
                prim["attributes"][key] = len(accessors) - 1
        gl_meshes.append({"name": name, "primitives": [prim]})
        nodes.append({"name": name, "mesh": len(gl_meshes) - 1})
    nodes.append({"name": "camera", "camera": 0, "translation": [0.0, 1.5, -0.3]})
    image_views = [view(png) for png in images]
    while len(buf) % 4:
        buf.append(0)
    gltf = {
        "asset": {"version": "2.0", "generator": generator},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": gl_meshes,
        "materials": materials,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.05,
                                                            "aspectRatio": aspect}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(buf)}],
    }
    if images:
        gltf["images"] = [{"bufferView": v, "mimeType": "image/png"} for v in image_views]
        gltf["samplers"] = [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497,
                             "wrapT": 10497}]
        gltf["textures"] = [{"sampler": 0, "source": k} for k in range(len(images))]
    if not path.lower().endswith(".glb"):
        gltf["buffers"][0]["uri"] = ("data:application/octet-stream;base64,"
                                     + base64.b64encode(bytes(buf)).decode())
        with open(path, "w") as f:
            json.dump(gltf, f)
        return tris
    js = json.dumps(gltf, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    with open(path, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(js) + 8 + len(buf)))
        f.write(struct.pack("<II", len(js), 0x4E4F534A) + js)
        f.write(struct.pack("<II", len(buf), 0x004E4942))
        f.write(buf)
    return tris


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    total = int(sys.argv[2]) if len(sys.argv) > 2 else 69000
    walls = room()
    # The blob takes what the walls leave: 2 (n_lat - 1) n_lon triangles.
    left = max(total - 2 * len(walls), 100)
    n_lat = max(4, int(round(math.sqrt(left / 4.0))))
    n_lon = max(8, int(round(left / (2.0 * (n_lat - 1)))))
    meshes = [("blob", blob(n_lat, n_lon, (0.0, 0.9, -3.0), 0.85), 0)] + walls
    tris = write_gltf(out, meshes)
    print(f"{out}: {tris} triangles (blob {n_lat} x {n_lon})")


if __name__ == "__main__":
    main()
