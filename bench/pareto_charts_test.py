#!/usr/bin/python3
"""Smoke test of pareto_charts.py (no CTest): targets and picks by hand, and one run on a made-up CSV into a
temporary folder.  usage: /usr/bin/python3 bench/pareto_charts_test.py"""
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pareto_charts  # noqa: E402

HEADER = ("effect,scene,method,resolution,time_ms,time_ms_min,time_ms_max,time_measure,error,error_measure,"
          "bytes,load_1min,reference,front\n")
CSV = HEADER + """voxelization,bunny,grid,64,1.0,0.9,1.1,kernels,0.02,chamfer_rel,32768,1.00,0,1
voxelization,bunny,grid,128,3.0,2.9,3.1,kernels,0.01,chamfer_rel,262144,1.00,0,1
voxelization,bunny,slice-center,128,4.0,3.9,4.1,kernels,0.012,chamfer_rel,262144,1.00,0,0
voxelization,bunny,slice-center,256,9.0,8.0,9.5,kernels,0.004,chamfer_rel,2097152,1.00,0,1
refraction,glass-sphere,reference-matched,,2.5,2.5,2.5,frame,0,image_rmse,0,1.00,1,1
refraction,glass-sphere,image-space,,2.0,1.9,2.1,frame,0.05,image_rmse,0,1.00,0,1
refraction,glass-sphere,voxel-multi-dda-smooth,64,3.0,2.9,3.2,frame,0.03,image_rmse,100,1.00,0,0
refraction,glass-sphere,voxel-two,64,3.5,3.4,3.6,frame,nan,image_rmse,100,1.00,0,0
"""


def run(time, error, reference=False):
    return {"_time": time, "_error": error, "method": f"m{time}", "resolution": "", "_reference": reference}


class ParetoCharts(unittest.TestCase):
    def test_fastest_within(self):
        rows = [run(1, 0.5), run(2, 0.2), run(3, 0.1), run(0.5, float("nan"))]
        self.assertEqual(pareto_charts.fastest_within(rows, 0.5)["_time"], 1)
        self.assertEqual(pareto_charts.fastest_within(rows, 0.2)["_time"], 2)
        self.assertEqual(pareto_charts.fastest_within(rows, 0.15)["_time"], 3)
        self.assertIsNone(pareto_charts.fastest_within(rows, 0.05))
        # A reference (error 0) meets every target: it is the pick wherever it is the fastest that does.
        rows.append(run(2.5, 0.0, reference=True))
        self.assertEqual(pareto_charts.fastest_within(rows, 0.15)["_time"], 2.5)
        self.assertEqual(pareto_charts.fastest_within(rows, 0.2)["_time"], 2)

    def test_targets(self):
        rows = [run(1, e) for e in (0.01, 0.02, 0.03, 0.04, 0.05)] + [run(9, float("nan")), run(5, 0.0, True)]
        # Quantiles 0.1, 0.25, 0.5, 0.75 of 0.01..0.05: 0.014, 0.02, 0.03, 0.04 (rounded up, 2 digits).
        self.assertEqual(pareto_charts.targets(rows), [0.014, 0.02, 0.03, 0.04])
        self.assertEqual(pareto_charts.round_up(0.01234), 0.013)

    def test_end_to_end(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "pareto.csv")
            with open(path, "w") as f:
                f.write(CSV)
            page = os.path.join(d, "docs", "pareto.md")
            images = os.path.join(d, "docs", "images", "pareto")
            pareto_charts.main([path, page, images, "--command", "voxr bench pareto --quick", "--device", "cpu"])
            self.assertEqual(sorted(os.listdir(images)), ["refraction.png", "voxelization.png"])
            with open(page) as f:
                text = f.read()
            self.assertIn("`voxr bench pareto --quick`", text)
            self.assertIn("](images/pareto/voxelization.png)", text)
            self.assertIn("](images/pareto/refraction.png)", text)
            lines = text.splitlines()
            start = lines.index("### voxelization: bunny")
            picks = [line for line in lines[start:] if line.startswith("| 0.")][:4]
            # Errors 0.004, 0.01, 0.012, 0.02: quantiles 0.0058, 0.0085, 0.011, 0.014 -> picks.
            self.assertEqual([p.split(" | ")[1:3] for p in picks],
                             [["slice-center", "256"], ["slice-center", "256"], ["grid", "128"], ["grid", "128"]])
            # The front's runs, fastest first; image-space has no resolution.
            self.assertIn("| image-space | - | 2 | [1.9, 2.1] | 0.05 | 0 |", text)
            self.assertIn("Pareto front (3 of 4 runs)", text)
            self.assertIn("Pareto front (2 of 4 runs)", text)
            # The reference is a run: it dominates the two voxel runs (slower, whatever their error), not
            # image-space (faster); every run is listed, off the front too.
            self.assertIn("The reference (reference-matched, 2.5 ms) dominates 2 of 3 runs; every run of: "
                          "voxel-multi-dda-smooth, voxel-two.", text)
            self.assertIn("| voxel-multi-dda-smooth | 64 | 3 | 0.03 |  | yes |", text)
            self.assertIn("| image-space | - | 2 | 0.05 | yes |  |", text)
            self.assertIn("| reference-matched | - | 2.5 | 0 | yes |  |", text)


if __name__ == "__main__":
    unittest.main()
