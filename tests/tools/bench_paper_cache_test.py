#!/usr/bin/env python3
"""tools/swellbench: the paper-scale cache is baked again exactly when the scene file or the
solver's numerics version changed since the last bake (its stamp), never reused stale.

    /usr/bin/python3 tests/tools/bench_paper_cache_test.py
"""
import json
import pathlib
import sys
import tempfile
import unittest
from unittest import mock

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from swellbench import common  # noqa: E402


class Result:
    rc = 0


class PaperCache(unittest.TestCase):
    def test_numerics_version_is_the_source_trees(self):
        text = (ROOT / "bake/include/swell/bake/numerics_version.h").read_text()
        self.assertIn("kNumericsVersion = %d;" % common.numerics_version(), text)

    def test_baked_once_then_again_when_the_scene_or_the_numerics_change(self):
        with tempfile.TemporaryDirectory() as tmp:
            ctx = common.Context(quick=True, log=None, out=tmp)
            bakes = []

            def fake_run(cmd, timeout=900):
                bakes.append(cmd)
                pathlib.Path(cmd[cmd.index("-o") + 1]).write_bytes(b"cache")
                return Result()

            ctx.run = fake_run
            cache = ctx.paper_cache()
            self.assertEqual(len(bakes), 1)
            self.assertIn(common.scene("surging.json"), bakes[0])
            ctx.paper_cache()
            self.assertEqual(len(bakes), 1, "an up-to-date cache is reused")
            stamp = json.loads(pathlib.Path(cache + ".stamp.json").read_text())
            self.assertEqual(stamp["numerics_version"], common.numerics_version())
            with mock.patch.object(common, "numerics_version", return_value=-1):
                ctx.paper_cache()
            self.assertEqual(len(bakes), 2, "another numerics version bakes again")
            with mock.patch.object(common, "file_sha256", return_value="edited"):
                ctx.paper_cache()
            self.assertEqual(len(bakes), 3, "an edited scene bakes again")
            pathlib.Path(cache).unlink()
            ctx.paper_cache()
            self.assertEqual(len(bakes), 4, "a missing cache is baked")
            pathlib.Path(cache + ".stamp.json").write_text("{broken")
            ctx.paper_cache()
            self.assertEqual(len(bakes), 5, "an unreadable stamp bakes again")


if __name__ == "__main__":
    unittest.main()
