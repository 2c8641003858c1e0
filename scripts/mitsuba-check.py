#!/usr/bin/env python3
"""Optional cross-check of voxr's exact refraction reference against Mitsuba 3 (never run in CI).

The script writes its own scene: a glass box standing exactly on a floor (its bottom face in the floor's
plane: the contact case of issue 19) and a turned glass box floating beside it, as OBJ files with a vertex
per face corner (flat normals in both renderers), a constant sky, a black floor (so a pixel shows only what
the glass reflects and transmits from the sky: no light-model difference, no shadows) and no light. It
renders them with `voxr render --refraction reference-full` (exact Fresnel at every interface, as Mitsuba's
`dielectric` BSDF; Beer-Lambert inside, as a homogeneous absorbing medium with `volpath`; --supersample^2
pixel centres averaged per pixel) and with Mitsuba (scalar_rgb, box-filtered pixels, --spp samples), and
prints the RMSE (linear RGB) on
  - the floating box's pixels (away from contacts), and
  - the standing box's pixels (rays that meet the glass-on-floor contact),
each on pixels 2 away from any silhouette or face edge, with Mitsuba's own noise (two seeds) beside them.
Needs Mitsuba 3 and numpy (docs/methods.md, "Cross-check against Mitsuba 3"):

    python3 -m venv build/mitsuba-venv && build/mitsuba-venv/bin/pip install mitsuba numpy
    build/mitsuba-venv/bin/python scripts/mitsuba-check.py --voxr build/voxr --out build/mitsuba-check
"""

import argparse
import json
import math
import os
import subprocess
import sys

import numpy as np

IOR = 1.5
SIGMA = [0.3, 0.15, 0.05]  # per unit length
SKY = [0.6, 0.7, 0.9]
CAMERA = {"position": [0.6, 2.6, 3.4], "look_at": [0.3, 0.35, 0.0], "up": [0, 1, 0], "fov_deg": 40}


def box_faces(lo, hi, rotate_y_deg=0.0, lift=(0.0, 0.0, 0.0)):
    """The 6 faces of box [lo, hi], turned about y and moved, as quads of 4 points wound outward."""
    c, s = math.cos(math.radians(rotate_y_deg)), math.sin(math.radians(rotate_y_deg))

    def place(p):
        x, y, z = p
        return (c * x + s * z + lift[0], y + lift[1], -s * x + c * z + lift[2])

    faces = []
    for axis in range(3):
        for side in (0, 1):
            u, v = (axis + 1) % 3, (axis + 2) % 3
            quad = []
            for cu, cv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = hi[axis] if side else lo[axis]
                p[u] = hi[u] if cu else lo[u]
                p[v] = hi[v] if cv else lo[v]
                quad.append(p)
            # (u, v, axis) is right-handed: this order faces +axis; reverse it for the low side.
            if not side:
                quad.reverse()
            faces.append([place(p) for p in quad])
    return faces


def write_obj(path, faces):
    """Quads as 2 triangles each, every face with vertices of its own (flat normals)."""
    with open(path, "w") as f:
        n = 0
        for quad in faces:
            for p in quad:
                f.write("v {:.9g} {:.9g} {:.9g}\n".format(*p))
            f.write(f"f {n + 1} {n + 2} {n + 3}\nf {n + 1} {n + 3} {n + 4}\n")
            n += 4


def write_scene(out, width, height):
    standing = box_faces([-0.5, 0.0, -0.5], [0.5, 0.8, 0.5], 0.0)  # bottom face at y = 0: on the floor
    floating = box_faces([-0.35, -0.35, -0.35], [0.35, 0.35, 0.35], 30.0, (1.3, 0.9, -0.4))
    floor = [[(-4.0, 0.0, -4.0), (-4.0, 0.0, 4.0), (4.0, 0.0, 4.0), (4.0, 0.0, -4.0)]]  # faces +y
    write_obj(os.path.join(out, "standing.obj"), standing)
    write_obj(os.path.join(out, "floating.obj"), floating)
    write_obj(os.path.join(out, "floor.obj"), floor)
    scene = {
        "materials": [
            {"name": "glass", "kind": "dielectric", "ior": IOR, "absorption": SIGMA},
            {"name": "floor", "kind": "opaque", "color": [0.0, 0.0, 0.0]},
        ],
        "meshes": [
            {"file": "standing.obj", "material": "glass"},
            {"file": "floating.obj", "material": "glass"},
            {"file": "floor.obj", "material": "floor"},
        ],
        "light": {"type": "directional", "direction": [0, -1, 0], "intensity": [0, 0, 0]},
        "camera": dict(CAMERA, width=width, height=height),
        "environment": {"color": SKY},
    }
    path = os.path.join(out, "scene.json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path


def render_mitsuba(mi, out, width, height, spp, seed):
    glass = {
        "type": "dielectric",
        "int_ior": IOR,
        "ext_ior": 1.0,
    }
    medium = {"type": "homogeneous", "albedo": 0.0, "sigma_t": {"type": "rgb", "value": SIGMA}, "scale": 1.0}
    scene = mi.load_dict({
        "type": "scene",
        "integrator": {"type": "volpath", "max_depth": 64, "rr_depth": 64},
        "sensor": {
            "type": "perspective",
            "fov_axis": "y",
            "fov": CAMERA["fov_deg"],
            "to_world": mi.ScalarTransform4f().look_at(origin=CAMERA["position"], target=CAMERA["look_at"],
                                                       up=CAMERA["up"]),
            "film": {"type": "hdrfilm", "width": width, "height": height, "rfilter": {"type": "box"},
                     "pixel_format": "rgb"},
            "sampler": {"type": "independent", "sample_count": spp, "seed": seed},
        },
        "sky": {"type": "constant", "radiance": {"type": "rgb", "value": SKY}},
        "standing": {"type": "obj", "filename": os.path.join(out, "standing.obj"), "face_normals": True,
                     "bsdf": glass, "interior": medium},
        "floating": {"type": "obj", "filename": os.path.join(out, "floating.obj"), "face_normals": True,
                     "bsdf": glass, "interior": medium},
        "floor": {"type": "obj", "filename": os.path.join(out, "floor.obj"), "face_normals": True,
                  "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.0, 0.0, 0.0]}}},
    })
    image = np.array(mi.render(scene), dtype=np.float64)[:, :, :3]
    # Which shape each pixel centre's camera ray meets first: 0 none, 1 standing, 2 floating, 3 floor; and
    # which face (its normal, rounded): pixels whose 3 x 3 neighbourhood meets one face only are compared.
    sensor = scene.sensors()[0]
    # (Mitsuba may merge the two glass meshes into one shape: told apart by where the hit is, x > 0.75.)
    first = np.zeros((height, width), dtype=np.int32)
    face = np.zeros((height, width), dtype=np.int64)
    for y in range(height):
        for x in range(width):
            ray, _ = sensor.sample_ray(0.0, 0.5, mi.ScalarPoint2f((x + 0.5) / width, (y + 0.5) / height),
                                       mi.ScalarPoint2f(0.5, 0.5))
            si = scene.ray_intersect(ray)
            if si.is_valid():
                first[y, x] = 3 if si.shape.id() == "floor" else 2 if si.p[0] > 0.75 else 1
                n = [int(round(float(si.n[c]) * 100)) + 100 for c in range(3)]
                face[y, x] = first[y, x] * 10**9 + n[0] * 10**6 + n[1] * 10**3 + n[2]
    return image, first, face


def interior(face, r):
    """Pixels whose (2r + 1)^2 neighbourhood meets one face only (no silhouette or crease edge nearby)."""
    out = np.ones(face.shape, dtype=bool)
    for dy in range(-r, r + 1):
        for dx in range(-r, r + 1):
            out &= np.roll(np.roll(face, dy, axis=0), dx, axis=1) == face
    out[:r, :] = out[-r:, :] = False
    out[:, :r] = out[:, -r:] = False
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--voxr", default="build/voxr")
    ap.add_argument("--out", default="build/mitsuba-check")
    ap.add_argument("--size", default="160x120")
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--refraction", default="reference-full", help="voxr's method (reference-full or reference)")
    ap.add_argument("--supersample", type=int, default=4,
                    help="voxr renders N x N pixel centres per pixel, averaged (a box filter, as Mitsuba's)")
    args = ap.parse_args()
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    width, height = (int(v) for v in args.size.split("x"))
    os.makedirs(args.out, exist_ok=True)
    scene = write_scene(args.out, width, height)
    voxr_exr = os.path.join(args.out, "voxr.exr")
    k = args.supersample
    subprocess.run([args.voxr, "render", scene, "--refraction", args.refraction, "--size",
                    f"{width * k}x{height * k}", "-o", voxr_exr, "--quiet"], check=True)
    ours = np.array(mi.Bitmap(voxr_exr), dtype=np.float64)[:, :, :3]
    ours = ours.reshape(height, k, width, k, 3).mean(axis=(1, 3))
    theirs, first, face = render_mitsuba(mi, args.out, width, height, args.spp, 0)
    again, _, _ = render_mitsuba(mi, args.out, width, height, args.spp, 1)  # Mitsuba's own noise
    mi.Bitmap(theirs.astype(np.float32)).write(os.path.join(args.out, "mitsuba.exr"))
    print(f"voxr --refraction {args.refraction} ({k}x{k} centres per pixel) against Mitsuba {mi.__version__} "
          f"(scalar_rgb, {args.spp} spp, {width}x{height}), linear RGB, pixels 2 away from any face edge:")
    keep = interior(face, 2)
    for name, label in ((2, "floating glass (away from contacts)"), (1, "glass standing on the floor (contact)")):
        mask = keep & (first == name)
        diff = (ours - theirs)[mask]
        noise = (again - theirs)[mask] / math.sqrt(2.0)  # one render's noise
        rmse = math.sqrt(float(np.mean(diff * diff)))
        print(f"  {label}: {int(mask.sum())} pixels, mean {float(np.mean(theirs[mask])):.3f}, RMSE {rmse:.2e}, "
              f"median |difference| {float(np.median(np.abs(diff))):.2e}, mean difference "
              f"{float(np.mean(diff)):+.2e}; Mitsuba's noise RMSE {math.sqrt(float(np.mean(noise * noise))):.2e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
