#!/usr/bin/env python3
"""Writes the seed corpus of the mesh fuzzers, fuzz/corpus/<format>/: a unit cube in every format (and one
concave face, so the constrained Delaunay triangulation runs), and of the environment image fuzzer,
fuzz/corpus/env_image/: tiny PNG, EXR and Radiance HDR images, each behind the byte that picks its extension
(fuzz/fuzz_env_image.cpp). Run once; the files are committed."""
import base64
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
CORNERS = [(i & 1, (i >> 1) & 1, (i >> 2) & 1) for i in range(8)]
QUADS = [(0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6)]
TRIS = [t for q in QUADS for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))]


def write(fmt, name, data):
    os.makedirs(os.path.join(HERE, "corpus", fmt), exist_ok=True)
    with open(os.path.join(HERE, "corpus", fmt, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def ply_header(fmt, face_props):
    return ("ply\nformat %s 1.0\ncomment unit cube\nelement vertex 8\nproperty float x\nproperty float y\n"
            "property float z\nelement face 6\n%send_header\n" % (fmt, face_props))


def main():
    # OFF: colour keyword, comments, RGBA per vertex and face.
    s = "COFF # unit cube\n# counts\n8 6 0\n"
    s += "".join("%d %d %d 255 0 0 255\n" % c for c in CORNERS)
    s += "".join("4 %d %d %d %d 0.5 0.5 0.5\n" % q for q in QUADS)
    write("off", "cube.off", s)
    write("off", "concave.off", "OFF\n6 1 0\n0 0 0\n2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\n6 0 1 2 3 4 5\n")

    # OBJ: v/vt/vn corners with negative (relative) indices.
    s = "# unit cube\nmtllib none.mtl\no cube\n" + "".join("v %d %d %d\n" % c for c in CORNERS)
    s += "vt 0 0\nvn 0 0 1\ng sides\n"
    s += "".join("f %s\n" % " ".join("%d/-1/-1" % (i - 8) for i in q) for q in QUADS)
    write("obj", "cube.obj", s)
    write("obj", "concave.obj", "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1//1 2 3 4 5 6\n")

    # PLY: ASCII; binary little endian with a face property before a `list uchar ushort` index list; big
    # endian with int indices and a double vertex property after the coordinates.
    s = ply_header("ascii", "property list uchar int vertex_indices\n")
    s += "".join("%d %d %d\n" % c for c in CORNERS) + "".join("4 %d %d %d %d\n" % q for q in QUADS)
    write("ply", "cube_ascii.ply", s)
    b = ply_header("binary_little_endian",
                   "property uchar flags\nproperty list uchar ushort vertex_indices\n").encode()
    b += b"".join(struct.pack("<3f", *c) for c in CORNERS)
    b += b"".join(struct.pack("<BB4H", 7, 4, *q) for q in QUADS)
    write("ply", "cube_binary_le.ply", b)
    b = ("ply\nformat binary_big_endian 1.0\nelement vertex 8\nproperty double x\nproperty double y\n"
         "property double z\nproperty double quality\nelement face 6\nproperty list uchar int vertex_index\n"
         "end_header\n").encode()
    b += b"".join(struct.pack(">4d", *c, 1.0) for c in CORNERS)
    b += b"".join(struct.pack(">B4i", 4, *q) for q in QUADS)
    write("ply", "cube_binary_be.ply", b)

    # STL: ASCII and binary.
    s = "solid cube\n"
    for t in TRIS:
        s += "facet normal 0 0 0\n outer loop\n"
        s += "".join("  vertex %d %d %d\n" % CORNERS[i] for i in t) + " endloop\nendfacet\n"
    write("stl", "cube_ascii.stl", s + "endsolid cube\n")
    b = b"binary cube".ljust(80, b"\0") + struct.pack("<I", len(TRIS))
    for t in TRIS:
        b += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *CORNERS[i]) for i in t) + b"\0\0"
    write("stl", "cube_binary.stl", b)

    # glTF with the buffer embedded as a base64 data URI, and the same as GLB.
    positions = b"".join(struct.pack("<3f", *c) for c in CORNERS)
    indices = b"".join(struct.pack("<H", i) for t in TRIS for i in t)
    buffer = positions + indices
    def gltf(uri):
        doc = {
            "asset": {"version": "2.0"},
            "scene": 0,
            "scenes": [{"nodes": [0]}],
            "nodes": [{"mesh": 0, "translation": [1, 0, 0]}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
            "accessors": [
                {"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3", "min": [0, 0, 0],
                 "max": [1, 1, 1]},
                {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"},
            ],
            "bufferViews": [
                {"buffer": 0, "byteOffset": 0, "byteLength": len(positions)},
                {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices)},
            ],
            "buffers": [{"byteLength": len(buffer)}],
        }
        if uri:
            doc["buffers"][0]["uri"] = uri
        return json.dumps(doc, separators=(",", ":"))
    write("gltf", "cube.gltf",
          gltf("data:application/octet-stream;base64," + base64.b64encode(buffer).decode()))
    j = gltf(None).encode()
    j += b" " * (-len(j) % 4)
    body = struct.pack("<I4s", len(j), b"JSON") + j + struct.pack("<I4s", len(buffer), b"BIN\0") + buffer
    write("glb", "cube.glb", struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body)

    env_image_seeds()


def png(width, height, color_type, bit_depth, rows, extra=b""):
    """A PNG of filter-0 rows (bytes each), optional chunks before IDAT."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    ihdr = struct.pack(">IIBBBBB", width, height, bit_depth, color_type, 0, 0, 0)
    idat = zlib.compress(b"".join(b"\0" + r for r in rows))
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + extra + chunk(b"IDAT", idat) + chunk(b"IEND", b"")


def exr(width, height, channels, pixel_type):
    """An uncompressed scanline OpenEXR file; channels by name (sorted), pixel_type 1 half or 2 float; texel
    values 0.25 * (x + y + channel index)."""
    def attr(name, kind, value):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value
    names = sorted(channels)
    chlist = b"".join(n.encode() + b"\0" + struct.pack("<iB3xii", pixel_type, 0, 1, 1) for n in names) + b"\0"
    window = struct.pack("<4i", 0, 0, width - 1, height - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + attr("channels", "chlist", chlist) +
              attr("compression", "compression", b"\0") + attr("dataWindow", "box2i", window) +
              attr("displayWindow", "box2i", window) + attr("lineOrder", "lineOrder", b"\0") +
              attr("pixelAspectRatio", "float", struct.pack("<f", 1)) +
              attr("screenWindowCenter", "v2f", struct.pack("<2f", 0, 0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    fmt = "<e" if pixel_type == 1 else "<f"
    blocks = []
    for y in range(height):
        data = b"".join(struct.pack(fmt, 0.25 * (x + y + c)) for c in range(len(names)) for x in range(width))
        blocks.append(struct.pack("<ii", y, len(data)) + data)
    offset = len(header) + 8 * height
    table = b""
    for b in blocks:
        table += struct.pack("<Q", offset)
        offset += len(b)
    return header + table + b"".join(blocks)


def env_image_seeds():
    # The first byte picks the extension: 0 .png, 1 .exr, 2 .hdr.
    rgba = [bytes([40 * x, 60 * y, 200, 255]) * 1 for y in range(2) for x in range(2)]
    write("env_image", "rgba.png", b"\0" + png(2, 2, 6, 8, [rgba[0] + rgba[1], rgba[2] + rgba[3]]))
    plte = struct.pack(">I", 6) + b"PLTE" + b"\xff\0\0\0\0\xff"
    plte += struct.pack(">I", zlib.crc32(b"PLTE\xff\0\0\0\0\xff"))
    write("env_image", "palette.png", b"\0" + png(2, 1, 3, 8, [b"\0\1"], plte))
    write("env_image", "grey16.png", b"\0" + png(1, 2, 0, 16, [b"\x12\x34", b"\xff\xff"]))
    write("env_image", "rgba_float.exr", b"\1" + exr(2, 2, ["R", "G", "B", "A"], 2))
    write("env_image", "grey_half.exr", b"\1" + exr(3, 1, ["Y"], 1))
    hdr = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 2\n"
    write("env_image", "flat.hdr", b"\2" + hdr + bytes([128, 64, 32, 129, 10, 20, 30, 128, 0, 0, 0, 0, 255, 255, 255, 130]))
    # Width 8: new-style run-length scanlines (2 2 width), one run per component.
    rle = b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=1.0\n\n-Y 1 +X 8\n" + bytes([2, 2, 0, 8])
    rle += b"".join(bytes([128 + 8, v]) for v in (100, 50, 25, 129))
    write("env_image", "rle.hdr", b"\2" + rle)


if __name__ == "__main__":
    main()
