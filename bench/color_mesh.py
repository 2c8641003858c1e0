#!/usr/bin/env python3
"""Writes the colour benchmark's mesh: an OBJ subdivided at edge midpoints (4^levels triangles per input
triangle, one midpoint per undirected edge, as voxr's subdivide_midpoint) as a binary PLY whose vertices carry
opaque RGBA colours from their position in the bounds (R, G, B = x, y, z from 0 to 255, as
bench_meshes.h color_by_position).

    bench/color_mesh.py data/meshes/bunny.obj 2 out/bunnyx16-color.ply
"""
import struct
import sys


def read_obj(path):
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "v":
                verts.append(tuple(float(x) for x in w[1:4]))
            elif w[0] == "f":
                idx = [int(t.split("/")[0]) - 1 for t in w[1:]]
                for k in range(1, len(idx) - 1):
                    tris.append((idx[0], idx[k], idx[k + 1]))
    return verts, tris


def subdivide(verts, tris):
    verts = list(verts)
    mid = {}

    def m(a, b):
        key = (a, b) if a < b else (b, a)
        if key not in mid:
            pa, pb = verts[a], verts[b]
            verts.append(tuple((pa[i] + pb[i]) * 0.5 for i in range(3)))
            mid[key] = len(verts) - 1
        return mid[key]

    out = []
    for a, b, c in tris:
        ab, bc, ca = m(a, b), m(b, c), m(c, a)
        out += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    return verts, out


def main():
    src, levels, dst = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    verts, tris = read_obj(src)
    for _ in range(levels):
        verts, tris = subdivide(verts, tris)
    lo = [min(v[i] for v in verts) for i in range(3)]
    hi = [max(v[i] for v in verts) for i in range(3)]
    size = [max(hi[i] - lo[i], 1e-30) for i in range(3)]
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(verts)}\n"
        "property float x\nproperty float y\nproperty float z\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n"
        f"element face {len(tris)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    with open(dst, "wb") as f:
        f.write(header.encode())
        vs = struct.Struct("<fffBBBB")
        for v in verts:
            c = [int(min(max((v[i] - lo[i]) / size[i], 0.0), 1.0) * 255.0 + 0.5) for i in range(3)]
            f.write(vs.pack(v[0], v[1], v[2], c[0], c[1], c[2], 255))
        fs = struct.Struct("<Biii")
        for t in tris:
            f.write(fs.pack(3, *t))
    print(f"{dst}: {len(verts)} vertices, {len(tris)} triangles")


if __name__ == "__main__":
    main()
