#!/usr/bin/env python3
"""A second wave gauge read from a kept regular-wave record's cache (docs/validation.md 7.55).

    /usr/bin/python3 docs/trials/interp_gauge.py KEPT_DIR OUT_DIR L0 DEPTH

KEPT_DIR is a `swell-validate regular-wave SCENE --keep DIR` folder (its .swell cache and
.probes.csv). OUT_DIR gets two probes CSVs with the same header and times:
- max.csv: the shipped gauge (bake/src/probes.cpp) read again from the cache's surface
  particles: the highest particle within l0 of the gauge, plus l0 / 2 (a check: it matches
  the kept CSV to float32 precision);
- interp.csv: the surface interpolated at the gauge: the top surface particles within 2.5 l0
  (a particle with another within 0.6 l0 along x and more than 0.4 l0 above it is dropped), a
  least-squares line weighted 1 - |dx| / 2.5 l0, read at the gauge, plus l0 / 2.
Fit either with `swell-validate --json [--set ...] regular-wave SCENE --probes CSV` (copy it
to DIR/<scene>.probes.csv for tools/wave_windows.py). Needs python3-numpy and python3-zstandard.
"""
import csv
import glob
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from swell_cache import Cache  # noqa: E402


def main(src, outdir, l0, h):
    cache = glob.glob(os.path.join(src, "*.swell"))[0]
    probes = glob.glob(os.path.join(src, "*.probes.csv"))[0]
    rows = list(csv.reader(open(probes)))
    hdr = rows[0]
    gauges = [float(g.split("_")[1]) for g in hdr[2:]]
    c = Cache(cache)
    os.makedirs(outdir, exist_ok=True)
    reach = 2.5 * l0
    with open(os.path.join(outdir, "max.csv"), "w") as fm, \
            open(os.path.join(outdir, "interp.csv"), "w") as fi:
        fm.write(",".join(hdr) + "\n")
        fi.write(",".join(hdr) + "\n")
        for k in range(len(c)):
            surface, _ = c.frame(k)
            a = np.asarray(surface, dtype=float).reshape(-1, 2)
            em, ei = [], []
            for g in gauges:
                p = a[np.abs(a[:, 0] - g) <= reach]
                strip = p[np.abs(p[:, 0] - g) <= l0]
                em.append(strip[:, 1].max() + 0.5 * l0 - h)
                under = [np.any((np.abs(p[:, 0] - x) < 0.6 * l0) & (p[:, 1] - y > 0.4 * l0))
                         for x, y in p]
                q = p[~np.array(under)]
                w = np.sqrt(1.0 - np.abs(q[:, 0] - g) / reach)
                A = np.stack([np.ones(len(q)), q[:, 0] - g], 1) * w[:, None]
                line = np.linalg.lstsq(A, q[:, 1] * w, rcond=None)[0]
                ei.append(line[0] + 0.5 * l0 - h)
            head = "%s,%s," % (rows[k + 1][0], rows[k + 1][1])
            fm.write(head + ",".join("%.9g" % v for v in em) + "\n")
            fi.write(head + ",".join("%.9g" % v for v in ei) + "\n")


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]))
