"""The Python module `swell` (tools/python, docs/python.md), run by ctest with Debian's python3:
caches as NumPy arrays (checked against the pure-Python reader tools/swell_cache.py), the replay
against the analytic wave a synthetic cache holds, the bake, and the errors as exceptions.

    SWELL_BIN=build/bin PYTHONPATH=build/python:tools /usr/bin/python3 -m unittest discover -s tests/python
"""
import math
import os
import shutil
import subprocess
import tempfile
import unittest

import numpy as np

import swell
import swell_cache  # tools/swell_cache.py, the pure-Python fallback reader

BIN = os.environ.get("SWELL_BIN", "build/bin")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def setUpModule():
    global TMP, WAVE, DAMAGED
    TMP = tempfile.mkdtemp(prefix="swell_python_")
    WAVE = os.path.join(TMP, "wave.swell")
    subprocess.run([os.path.join(BIN, "swell-cache"), "synth", WAVE, "--frames", "200",
                    "--surface", "400", "--splash", "3"], check=True, capture_output=True)
    DAMAGED = os.path.join(TMP, "damaged.swell")
    with open(WAVE, "rb") as f, open(DAMAGED, "wb") as g:
        g.write(f.read()[:5000])


def tearDownModule():
    shutil.rmtree(TMP, ignore_errors=True)


class CacheTest(unittest.TestCase):
    def test_frames_are_numpy_arrays_equal_to_the_pure_python_reader(self):
        c = swell.Cache(WAVE)
        ref = swell_cache.Cache(WAVE)
        self.assertEqual(len(c), 200)
        self.assertEqual(c.frame_count, len(ref))
        self.assertEqual(c.domain, ref.domain)
        self.assertEqual(c.metadata, ref.metadata)
        self.assertAlmostEqual(c.frame_seconds, ref.dt * ref.frame_interval)
        for i in (0, 17, 199):
            f = c.frame(i)
            surface, splash = ref.frame(i)
            self.assertEqual(f["surface"].dtype, np.float32)
            self.assertEqual(f["surface"].shape, (400, 2))
            self.assertEqual(f["splash"].shape, (3, 4))
            np.testing.assert_array_equal(f["surface"], np.array(surface, dtype=np.float32))
            np.testing.assert_array_equal(f["splash"], np.array(splash, dtype=np.float32))
        np.testing.assert_array_equal(c[-1]["surface"], c.frame(199)["surface"])

    def test_errors(self):
        with self.assertRaisesRegex(swell.CacheError, "/nonexistent.swell"):
            swell.Cache("/nonexistent.swell")
        with self.assertRaisesRegex(swell.CacheError, "damaged.swell"):
            swell.Cache(DAMAGED)
        with self.assertRaises(IndexError):
            swell.Cache(WAVE).frame(200)


class ReplayTest(unittest.TestCase):
    def test_shows_the_wave_the_cache_holds(self):
        """F = 0: every slice shows the frame of time t, which holds the analytic wave."""
        c = swell.Cache(WAVE)
        m = c.metadata
        r = swell.Replay(c, cells=(64, 8), fluctuation=0.0,
                         params={"policy": "clamp", "window": "all"})
        g = r.grid
        x = g["x0"] + (np.arange(g["cells_x"]) + 0.5) * g["dx"]
        for t in (0.4, 2.2):
            ph = 2 * math.pi / m["wavelength_m"] * x - 2 * math.pi / m["period_s"] * t
            wave = m["depth_m"] + m["amplitude_m"] * (np.cos(ph) + 0.2 * np.cos(2 * ph))
            r.advance(t)
            h = r.heights()
            self.assertEqual(h.shape, (8, 64))
            self.assertLess(np.abs(h - wave[None, :]).max(), 0.002)

    def test_run_sample_splashes_and_seeds(self):
        c = swell.Cache(WAVE)
        r = swell.Replay(c, cells=(32, 32), seed=4)
        fields = r.run([0.0, 0.5, 1.0])
        self.assertEqual(fields.shape, (3, 32, 32))
        self.assertEqual(fields.dtype, np.float32)
        r.advance(0.5)
        np.testing.assert_array_equal(r.heights(), fields[1])
        g = r.grid
        h = r.sample([g["x0"] + 3.5 * g["dx"], g["x0"] - 1.0], [5.5 * g["dz"], 0.1])
        self.assertAlmostEqual(h[0], float(fields[1][5, 3]), places=6)
        self.assertTrue(math.isnan(h[1]))
        sprites = r.splashes()
        self.assertEqual(sprites.shape[1], 4)
        self.assertGreater(len(sprites), 0)
        same = swell.Replay(c, cells=(32, 32), seed=4).run([0.5])
        other = swell.Replay(c, cells=(32, 32), seed=5).run([0.5])
        np.testing.assert_array_equal(same[0], fields[1])
        self.assertFalse(np.array_equal(other[0], fields[1]))
        self.assertEqual(r.params["params"]["seed"], 4)

    def test_other_modes(self):
        c = swell.Cache(WAVE)
        ripple = swell.Replay(c, mode="ripple", cells=(32, 32), ripple={"angles_degrees": [0, 45]})
        whirl = swell.Replay(c, mode="whirlpool", cells=(32, 32))
        for r in (ripple, whirl):
            self.assertTrue(np.isfinite(r.run([1.0])).all())

    def test_bad_parameters_raise_value_errors_naming_them(self):
        c = swell.Cache(WAVE)
        with self.assertRaisesRegex(ValueError, r"fluctuation must be in \[0, 1\].*got 2"):
            swell.Replay(c, fluctuation=2.0)
        with self.assertRaisesRegex(ValueError, "unknown key bogus"):
            swell.Replay(c, params={"bogus": 1})
        with self.assertRaisesRegex(ValueError, "above the memory budget"):
            swell.Replay(c, memory_budget_gib=1e-6)
        with self.assertRaisesRegex(ValueError, "set seed in the Replay keyword arguments"):
            swell.Replay(c, params={"seed": 3})
        with self.assertRaisesRegex(ValueError, "cells"):
            swell.Replay(c, cells=(0, 4))
        with self.assertRaisesRegex(ValueError, "mode"):
            swell.Replay(c, mode="spiral")
        with self.assertRaisesRegex(ValueError, "splash.artificial_per_real"):
            swell.Replay(c, splash={"artificial_per_real": "many"})
        with self.assertRaisesRegex(ValueError, "finite"):
            swell.Replay(c, cells=(16, 16)).advance(float("nan"))


class BakeTest(unittest.TestCase):
    def test_bake_with_overrides_writes_a_cache_and_returns_the_summary(self):
        out = os.path.join(TMP, "surging.swell")
        s = swell.bake(os.path.join(ROOT, "scenes", "surging_small.json"), out,
                       overrides=["solver.end_time=0.3"], threads=1)
        self.assertGreater(s["frames"], 1)
        c = swell.Cache(out)
        self.assertEqual(len(c), s["frames"])
        self.assertIn("solver.end_time=0.3", c.metadata["overrides"])

    def test_scene_errors(self):
        out = os.path.join(TMP, "never.swell")
        with self.assertRaisesRegex(swell.SceneError, "solver.dt"):
            swell.bake(os.path.join(ROOT, "scenes", "surging_small.json"), out,
                       overrides=["solver.dt=-1"])
        with self.assertRaisesRegex(swell.SceneError, "nothing.json"):
            swell.bake(os.path.join(TMP, "nothing.json"), out)
        self.assertFalse(os.path.exists(out))


if __name__ == "__main__":
    unittest.main()
