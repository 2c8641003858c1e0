#!/usr/bin/python3
"""Smoke test of shadow_charts.py (no CTest): the Pareto front by hand, and one run on a made-up CSV into a
temporary folder.  usage: /usr/bin/python3 bench/shadow_charts_test.py"""
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import shadow_charts  # noqa: E402

CSV = """scene,method,mode,resolution,frame_ms,frame_ms_min,frame_ms_max,rmse,max_abs,share_over_0.05,psnr
tree,slice,conservative,128,4.0,3.8,4.4,0.010,0.05,0.02,40
tree,slice,conservative,256,9.0,8.5,9.9,0.004,0.02,0.01,48
tree,slicemap,uniform,256,5.0,4.9,5.2,0.020,0.09,0.08,34
tree,slicemap,uniform,64,1.0,0.9,1.1,0.080,0.30,0.30,22
foliage,slice,centre,128,6.0,5.5,6.5,nan,nan,nan,nan
foliage,slice,centre,256,12.0,11.0,13.0,0.003,0.01,0.00,50
"""

# As voxr bench refraction writes it: empty step, normals and res cells for the methods without a grid.
REFRACTION_CSV = """scene,triangles,method,step,normals,res,frame_ms,frame_ms_min,frame_ms_max,rmse,psnr,angle_mean_deg
ball,960,reference-matched,,,,80.0,80.0,80.0,0.000000,inf,0.0000
ball,960,voxel-multi,dda,smooth,64,3.0,2.9,3.2,0.050000,26.0,4.0000
ball,960,voxel-multi,dda,smooth,256,9.0,8.8,9.5,0.020000,34.0,1.5000
ball,960,voxel-multi,papers,voxel,256,8.0,7.9,8.2,0.060000,24.4,nan
ball,960,image-space,,,,2.0,1.9,2.1,0.040000,28.0,6.0000
"""


def run(time, error):
    return {"_time": time, "_error": error}


class ShadowCharts(unittest.TestCase):
    def test_pareto(self):
        rows = [run(1, 0.5), run(2, 0.2), run(3, 0.3), run(2, 0.2), run(4, float("nan")), run(5, 0.1)]
        front = shadow_charts.pareto(rows)
        self.assertEqual([(r["_time"], r["_error"]) for r in front], [(1, 0.5), (2, 0.2), (2, 0.2), (5, 0.1)])
        # As a score (higher is better), (1, 0.5) is both the fastest and the best: the whole front.
        front = shadow_charts.pareto(rows, higher_is_better=True)
        self.assertEqual([(r["_time"], r["_error"]) for r in front], [(1, 0.5)])

    def test_end_to_end(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "shadows.csv")
            with open(path, "w") as f:
                f.write(CSV)
            out = os.path.join(d, "out")
            shadow_charts.main([path, out])
            self.assertEqual(sorted(os.listdir(out)), ["foliage.png", "shadows.md", "tree.png"])
            table = open(os.path.join(out, "shadows.md")).read().splitlines()
            rows = [line for line in table if line.startswith("| **P** |") or line.startswith("|  |")]
            # Sorted by scene, method, mode, resolution; slicemap 256 (5 ms, 0.02) is beaten by slice 128.
            self.assertEqual([r.split(" | ")[1:5] for r in rows],
                             [["foliage", "slice", "centre", "128"], ["foliage", "slice", "centre", "256"],
                              ["tree", "slice", "conservative", "128"], ["tree", "slice", "conservative", "256"],
                              ["tree", "slicemap", "uniform", "64"], ["tree", "slicemap", "uniform", "256"]])
            self.assertEqual([r.startswith("| **P**") for r in rows], [False, True, True, True, True, False])

    def test_refraction_columns(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "refraction.csv")
            with open(path, "w") as f:
                f.write(REFRACTION_CSV)
            for error in ("rmse", "angle_mean_deg"):
                out = os.path.join(d, "charts", error)
                shadow_charts.main([path, out, "--error-column", error, "--group-columns", "method,step,normals",
                                    "--label-column", "res"])
                self.assertEqual(sorted(os.listdir(out)), ["ball.png", "refraction.md"])
                table = open(os.path.join(out, "refraction.md")).read().splitlines()
                rows = [line for line in table if line.startswith("| **P** |") or line.startswith("|  |")]
                # Sorted by method, step, normals, res; empty cells stay empty.
                self.assertEqual([r.split(" | ")[3:7] for r in rows],
                                 [["image-space", "", "", ""], ["reference-matched", "", "", ""],
                                  ["voxel-multi", "dda", "smooth", "64"], ["voxel-multi", "dda", "smooth", "256"],
                                  ["voxel-multi", "papers", "voxel", "256"]])
                # rmse: image-space (2 ms) beats voxel 64 (3 ms, 0.05); the reference (error 0) is on the front.
                # angle: the NaN is never on the front; image-space (2 ms, 6 deg), 64 (3 ms, 4 deg),
                # 256 (9 ms, 1.5 deg) and the reference (0 deg).
                expected = {"rmse": [True, True, False, True, False],
                            "angle_mean_deg": [True, True, True, True, False]}[error]
                self.assertEqual([r.startswith("| **P**") for r in rows], expected, error)


if __name__ == "__main__":
    unittest.main()
