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


if __name__ == "__main__":
    unittest.main()
