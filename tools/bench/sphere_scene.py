#!/usr/bin/env python3
"""Writes a ~100k-triangle benchmark scene as a self-contained glTF (numpy only).

A smooth UV sphere (default 320 segments x 160 rings = 101,760 triangles, no degenerate ones
at the poles) on a floor, lit by a one-sided rectangular area light, seen by a perspective
camera. For throughput runs on a mesh bigger than the Cornell
box:

    python3 tools/bench/sphere_scene.py /tmp/sphere100k.gltf
    blueshift bench --scene /tmp/sphere100k.gltf --width 512 --height 512 --spp 16 --bounces 0
"""

import argparse
import base64
import json

import numpy as np


def uv_sphere(segments, rings):
    th = np.linspace(0.0, np.pi, rings + 1)
    ph = np.linspace(0.0, 2.0 * np.pi, segments + 1)
    t, p = np.meshgrid(th, ph, indexing="ij")
    pos = np.stack([np.sin(t) * np.cos(p), np.cos(t), np.sin(t) * np.sin(p)], -1).reshape(-1, 3)
    idx = []
    w = segments + 1
    for i in range(rings):
        for j in range(segments):
            a, b, c, d = i * w + j, (i + 1) * w + j, (i + 1) * w + j + 1, i * w + j + 1
            if i != rings - 1:  # the pole rows have one triangle per quad
                idx.append((a, b, c))
            if i != 0:
                idx.append((a, c, d))
    return pos.astype(np.float32), pos.astype(np.float32), np.array(idx, dtype=np.uint32)


def quad(size, y, flip=False):
    s = size
    pos = np.array([[-s, y, -s], [s, y, -s], [s, y, s], [-s, y, s]], np.float32)
    n = np.array([[0, -1 if flip else 1, 0]] * 4, np.float32)
    idx = np.array([[0, 1, 2], [0, 2, 3]] if flip else [[0, 2, 1], [0, 3, 2]], np.uint32)
    return pos, n, idx


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--segments", type=int, default=320)
    ap.add_argument("--rings", type=int, default=160)
    a = ap.parse_args()

    meshes = [("sphere", *uv_sphere(a.segments, a.rings), 0),
              ("floor", *quad(4.0, -1.0), 1),
              ("light", *quad(0.6, 2.5, flip=True), 2)]
    buf, views, accessors, gltf_meshes = bytearray(), [], [], []
    for name, pos, nrm, idx, mat in meshes:
        attrs = {}
        for key, arr, target in (("POSITION", pos, 34962), ("NORMAL", nrm, 34962), (None, idx, 34963)):
            while len(buf) % 4:
                buf.append(0)
            data = arr.tobytes()
            views.append({"buffer": 0, "byteOffset": len(buf), "byteLength": len(data), "target": target})
            buf.extend(data)
            acc = {"bufferView": len(views) - 1, "count": int(arr.size if key is None else arr.shape[0]),
                   "componentType": 5125 if key is None else 5126, "type": "SCALAR" if key is None else "VEC3"}
            if key == "POSITION":
                acc["min"], acc["max"] = pos.min(0).tolist(), pos.max(0).tolist()
            accessors.append(acc)
            if key:
                attrs[key] = len(accessors) - 1
        gltf_meshes.append({"name": name, "primitives": [{"attributes": attrs, "indices": len(accessors) - 1, "material": mat}]})
    doc = {
        "asset": {"version": "2.0", "generator": "blueshift tools/bench/sphere_scene.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [{"mesh": 0}, {"mesh": 1}, {"mesh": 2},
                  {"camera": 0, "translation": [0.0, 0.6, 4.2], "rotation": [-0.0705, 0.0, 0.0, 0.9975]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.75, "aspectRatio": 1.0, "znear": 0.01}}],
        "materials": [
            {"name": "sphere", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.5, 1], "metallicFactor": 0.0, "roughnessFactor": 0.4}},
            {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.7, 0.7, 1], "metallicFactor": 0.0, "roughnessFactor": 1.0}},
            {"name": "light", "emissiveFactor": [1, 1, 1], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 20.0}},
             "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]}},
        ],
        "meshes": gltf_meshes,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(buf), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf)).decode()}],
    }
    with open(a.out, "w") as f:
        json.dump(doc, f)
    tris = sum(len(m[3]) for m in meshes)
    print(f"wrote {a.out}: {tris} triangles ({len(meshes[0][3])} in the sphere)")


if __name__ == "__main__":
    main()
