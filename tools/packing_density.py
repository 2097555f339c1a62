#!/usr/bin/env python3
"""How much area a hexagonal packing needs to reach the square lattice's number density n0,
per number-density kernel and radius (docs/validation.md, Lattice constants; the still tank's
bed pressure).

MPS takes n0 from a square lattice of spacing l0. Water that the flow and the shifting reorder
towards a hexagonal packing is held at n = n0 by the density relaxation; where the hexagonal
packing reaches n0 in less area than the square lattice, the water shrinks by that much.
Prints, for each kernel and radius (in l0), that area ratio (1 = no volume drift), and for
the MPS kernel the number density n / n0 and the neighbour-distribution asymmetry
|sum (r_j - r_i) w| / (n0 l0) (the solver's free-surface test) of the first rows under a flat
lattice surface: the density relaxation asks a truncated row for n0 all the same.

    /usr/bin/python3 tools/packing_density.py
"""
import math


def mps(r, re):  # Koshizuka & Oka 1996
    return re / r - 1.0


def wendland(r, re):  # Wendland C2 (2D), unnormalised
    q = r / re
    return (1.0 - q) ** 4 * (1.0 + 4.0 * q)


def density(points, re, w):
    return sum(w(r, re) for r in (math.hypot(x, y) for x, y in points) if 0.0 < r < re)


def lattices(k=8):
    square = [(i, j) for i in range(-k, k + 1) for j in range(-k, k + 1)]
    a = math.sqrt(2.0 / math.sqrt(3.0))  # one unit of area per particle
    hexagonal = [((i + 0.5 * (j % 2)) * a, j * a * math.sqrt(3.0) / 2.0)
                 for i in range(-k, k + 1) for j in range(-k, k + 1)]
    return square, hexagonal


def area_ratio(re, w):
    square, hexagonal = lattices()
    n0 = density(square, re, w)
    lo, hi = 0.8, 1.2  # scale of the hexagonal lattice; n falls as it grows
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if density([(x * mid, y * mid) for x, y in hexagonal], re, w) > n0:
            lo = mid
        else:
            hi = mid
    return (0.5 * (lo + hi)) ** 2


def surface_rows(re, w, rows=3, k=8):
    """(n / n0, asymmetry) of the particle `depth` rows under a flat lattice surface."""
    square = [(i, j) for i in range(-k, k + 1) for j in range(-k, k + 1)]
    n0 = density(square, re, w)
    out = []
    for depth in range(rows):
        present = [(x, y) for x, y in square if y <= depth]  # the surface row is y = depth
        n = density(present, re, w)
        fy = sum(y * w(math.hypot(x, y), re) for x, y in present if 0.0 < math.hypot(x, y) < re)
        out.append((n / n0, abs(fy) / n0))
    return out


def main():
    print("kernel    re (l0)  hexagonal area at n = n0 / square lattice area")
    for name, w in (("mps", mps), ("wendland", wendland)):
        for re in (2.1, 2.4, 2.6, 2.8, 3.0, 3.1):
            print(f"{name:9s} {re:7.1f}  {area_ratio(re, w):.4f}")
    print()
    print("mps kernel, rows under a flat surface (row 1 = the surface): n / n0, asymmetry")
    for re in (2.1, 2.8, 3.0):
        cells = "  ".join(f"row {d + 1}: {n:.3f}, {f:.3f}"
                          for d, (n, f) in enumerate(surface_rows(re, mps)))
        print(f"re {re:.1f} l0  {cells}")


if __name__ == "__main__":
    main()
