#!/usr/bin/env python3
"""What Goring's stroke makes of a solitary wave with no numerical damping: the reference for
the height the solitary-wave check loses (docs/validation.md, Solitary wave).

Goring (1978) moves the piston so that the water in front of it is Boussinesq's first-order
wave, eta = H sech^2(k (x - c t)) with k = sqrt(3 H / (4 h^3)) and depth-mean velocity
u = c eta / (h + eta), c = sqrt(g (h + H)) (bake/src/piston_motion.cpp). That is not a
solitary wave of the fully nonlinear equations, whose crest is wider for its height, so it
adjusts as it travels: it sheds a tail and its crest falls. This tool evolves that wave (as
initial values) under the Serre-Green-Naghdi equations (fully nonlinear, weakly dispersive;
flat bed, no viscosity), in the form of Clamond, Dutykh & Mitsotakis (2017):

    h_t + (h u)_x = 0,
    q_t + (q u - u^2 / 2 + g h - h^2 u_x^2 / 2)_x = 0,   q = u - (h^3 u_x)_x / (3 h),

periodic, pseudo-spectral in x (2/3 dealiasing), classical RK4 in time; u from q by conjugate
gradients preconditioned by the still water's operator. It reads each gauge's record the way
`swell-validate solitary-wave` does (a parabola at the top, the half-crest crossings
interpolated): the crest's height over H, its time, and the time the record stays above half
the crest against Boussinesq's wave of that crest (the width error;
the SGN solitary wave of a crest A is wider than Boussinesq's by sqrt(1 + A / h)), and over the
gauges the height lost and the celerity against sqrt(g (h + A)). The crest starts at the
piston's mid-stroke, so a gauge at x reads the wave after x - stroke / 2 of travel. Bed friction, which theory puts at about 1 % over 20 h at this
scale (Keulegan 1948), is not in it.

    /usr/bin/python3 tools/sgn_solitary.py                      # scenes/solitary_wave.json's wave
    /usr/bin/python3 tools/sgn_solitary.py --gauges 2,4,6,8,10,12 --json
"""
import argparse
import json
import math
import sys

import numpy as np

G = 9.81


class Sgn:
    """The SGN equations on a periodic domain of `length` m sampled at n points, still depth h0."""

    def __init__(self, length, n, h0):
        self.x = np.arange(n) * (length / n)
        self.k = 2.0 * np.pi * np.fft.rfftfreq(n, length / n)
        self.keep = self.k < (2.0 / 3.0) * self.k[-1]
        self.still = h0 + h0 ** 3 * self.k ** 2 / 3.0  # the operator below for h = h0, in Fourier space
        self.n = n

    def dx(self, f):
        return np.fft.irfft(1j * self.k * np.fft.rfft(f), self.n)

    def dealias(self, f):
        return np.fft.irfft(np.where(self.keep, np.fft.rfft(f), 0.0), self.n)

    def q_of(self, h, u):
        return u - self.dx(h ** 3 * self.dx(u)) / (3.0 * h)

    def u_of(self, h, q, u, tol=1e-12, max_iter=500):
        """Solves h u - (h^3 u_x)_x / 3 = h q (symmetric positive definite) from the guess u."""
        h3 = h ** 3

        def op(v):
            return h * v - self.dx(h3 * self.dx(v)) / 3.0

        def precondition(r):
            return np.fft.irfft(np.fft.rfft(r) / self.still, self.n)

        b = h * q
        r = b - op(u)
        z = precondition(r)
        p = z.copy()
        rz = r @ z
        scale = math.sqrt(b @ b) or 1.0
        for _ in range(max_iter):
            if math.sqrt(r @ r) <= tol * scale:
                return u
            ap = op(p)
            alpha = rz / (p @ ap)
            u = u + alpha * p
            r = r - alpha * ap
            z = precondition(r)
            rz, rz_old = r @ z, rz
            p = z + (rz / rz_old) * p
        raise RuntimeError("sgn_solitary: the velocity solve did not converge in %d iterations" % max_iter)

    def rates(self, h, q, u):
        u = self.u_of(h, q, u)
        ux = self.dx(u)
        return -self.dx(h * u), -self.dx(q * u - 0.5 * u * u + G * h - 0.5 * h * h * ux * ux), u

    def step(self, h, q, u, dt):
        a1, b1, u = self.rates(h, q, u)
        a2, b2, u = self.rates(h + 0.5 * dt * a1, q + 0.5 * dt * b1, u)
        a3, b3, u = self.rates(h + 0.5 * dt * a2, q + 0.5 * dt * b2, u)
        a4, b4, u = self.rates(h + dt * a3, q + dt * b3, u)
        h = self.dealias(h + dt / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4))
        q = self.dealias(q + dt / 6.0 * (b1 + 2.0 * b2 + 2.0 * b3 + b4))
        return h, q, u


def boussinesq_k(height, depth):
    """Boussinesq's (and Goring's) sech^2 wavenumber, sqrt(3 H / (4 h^3))."""
    return math.sqrt(3.0 * height / (4.0 * depth ** 3))


def sgn_k(height, depth):
    """The SGN equations' exact solitary wave: sqrt(3 a / (4 h^2 (h + a)))."""
    return math.sqrt(3.0 * height / (4.0 * depth ** 2 * (depth + height)))


def goring_stroke(height, depth):
    """Goring's stroke, sqrt(16 H h / 3)."""
    return math.sqrt(16.0 * height * depth / 3.0)


def half_height_duration(amplitude, depth, k=None):
    """The time a record of a sech^2 wave of crest `amplitude` stays above half of it,
    2 acosh(sqrt 2) / (k c), c = sqrt(g (h + A)); k defaults to Boussinesq's for that crest (the
    width the solitary-wave check compares with, bake/validation/src/solitary_wave.cpp)."""
    k = k or boussinesq_k(amplitude, depth)
    return 2.0 * math.acosh(math.sqrt(2.0)) / (k * math.sqrt(G * (depth + amplitude)))


def read_crest(t, eta):
    """(crest height, crest time, time above half the crest) of one gauge's record: the crest from
    a parabola through the highest sample and its neighbours, the crossings interpolated."""
    p = int(np.argmax(eta))
    if not (0 < p < len(eta) - 1) or eta[0] >= 0.5 * eta[p] or eta[-1] >= 0.5 * eta[p]:
        raise RuntimeError("sgn_solitary: a gauge's record does not hold its whole crest")
    ym, y0, yp = eta[p - 1], eta[p], eta[p + 1]
    curvature = ym - 2.0 * y0 + yp
    s = 0.5 * (ym - yp) / curvature if curvature < 0.0 else 0.0
    top = y0 - 0.25 * (ym - yp) * s
    half = 0.5 * top
    a, b = p, p
    while eta[a] >= half:
        a -= 1
    while eta[b] >= half:
        b += 1

    def cross(k0, k1):
        return t[k0] + (t[k1] - t[k0]) * (half - eta[k0]) / (eta[k1] - eta[k0])

    return top, t[p] + s * (t[p + 1] - t[p]), cross(b - 1, b) - cross(a, a + 1)


def evolve(height, depth, k, distances, cells_per_depth=20.0, dt=None):
    """A sech^2 wave of `height` and wavenumber k, u = c eta / (h + eta), c = sqrt(g (h + height)),
    its crest starting at x = 0, evolved until it has passed gauges at `distances` (m, ascending).
    Returns, per gauge, (crest height, crest time, time above half the crest), and the relative
    mass drift."""
    times, records, drift = series(height, depth, k, distances, cells_per_depth, dt)
    return [read_crest(times, records[:, g]) for g in range(len(distances))], drift


def series(height, depth, k, distances, cells_per_depth=20.0, dt=None):
    """evolve's run: (times, eta at each gauge after every step [step, gauge], mass drift)."""
    reach = max(distances)
    start = 8.0 / k  # the wave's back falls below 1e-6 of its height there
    length = start + reach + 11.0 / k + 0.25 * reach  # its front, and room for the tail it sheds
    n = 1 << max(10, math.ceil(math.log2(length * cells_per_depth / depth)))
    model = Sgn(length, n, depth)
    spacing = length / n
    c = math.sqrt(G * (depth + height))
    eta = height / np.cosh(k * (model.x - start)) ** 2
    h = depth + eta
    u = c * eta / h
    q = model.q_of(h, u)
    dt = dt or 0.25 * spacing / c  # RK4 on the dealiased spectrum: well inside its limit
    at = (start + np.asarray(distances)) / spacing
    left = np.floor(at).astype(int)
    frac = at - left
    mass = h.sum()
    times, records = [0.0], [(1.0 - frac) * eta[left] + frac * eta[left + 1]]
    t = 0.0
    while t * c < reach + 3.0 / k + 0.1 * reach:  # the last crest and its half-height have passed
        h, q, u = model.step(h, q, u, dt)
        t += dt
        eta = h - depth
        times.append(t)
        records.append((1.0 - frac) * eta[left] + frac * eta[left + 1])
    return np.asarray(times), np.asarray(records), (h.sum() - mass) / mass


def goring_distances(height, depth, gauges):
    """(Boussinesq's k, half the stroke, each gauge's distance from where the SGN run starts the
    crest): the stroke's crest passes the piston at mid-stroke. Raises ValueError unless there are
    two or more gauges, rising, beyond half the stroke."""
    offset = 0.5 * goring_stroke(height, depth)
    at = [g - offset for g in gauges]
    if len(gauges) < 2 or at[0] <= 0.0 or any(b <= a for a, b in zip(at, at[1:])):
        raise ValueError("need two or more gauges, rising, beyond half the stroke (%.3f m)" % offset)
    return boussinesq_k(height, depth), offset, at


def goring_series(height, depth, gauges, cells_per_depth=20.0):
    """Goring's wave under SGN as the gauges (m from the piston's rest position) record it:
    (times from the piston's start, eta at each gauge [step, gauge]). The stroke's crest passes
    the piston at mid-stroke, (4 / k + stroke / 2) / c after the start (Goring's
    eta = H sech^2(k (c t - X) - 4)), where the SGN run starts it."""
    k, offset, at = goring_distances(height, depth, gauges)
    times, records, _ = series(height, depth, k, at, cells_per_depth)
    return times + (4.0 / k + offset) / math.sqrt(G * (depth + height)), records


def goring_record(height, depth, gauges, cells_per_depth=20.0):
    """Goring's wave under SGN read at the gauges (m from the piston's rest position) as the
    solitary-wave check reads its records: a dict with each gauge's crest height over `height`,
    crest time (from the crest's start at mid-stroke) and width error (the time above half the
    crest against Boussinesq's wave of that crest), the height lost between the first and last
    gauge, and the celerity over the gauges against sqrt(g (h + A)), A the crests' mean."""
    k, offset, at = goring_distances(height, depth, gauges)
    crests, drift = evolve(height, depth, k, at, cells_per_depth)
    amplitudes = [a for a, _, _ in crests]
    times = [t for _, t, _ in crests]
    slope = np.polyfit(times, gauges, 1)[0]
    mean_a = sum(amplitudes) / len(amplitudes)
    return {"height": height, "depth": depth, "gauges": list(gauges), "stroke": 2.0 * offset,
            "amplitude_over_height": [a / height for a in amplitudes], "crest_times": times,
            "width_errors": [w / half_height_duration(a, depth) - 1.0 for a, _, w in crests],
            "lost": 1.0 - amplitudes[-1] / amplitudes[0],
            "celerity": float(slope), "celerity_error": float(slope / math.sqrt(G * (depth + mean_a)) - 1.0),
            "mass_drift": float(drift), "cells_per_depth": cells_per_depth}


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--height", type=float, default=0.04, help="H, m (scenes/solitary_wave.json: 0.04)")
    ap.add_argument("--depth", type=float, default=0.2, help="h, m (0.2)")
    ap.add_argument("--gauges", default="2,3,4,5,6", help="m from the piston's rest position")
    ap.add_argument("--cells", type=float, default=20.0, help="grid points per depth (20)")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args(argv)
    if not (0.0 < args.depth <= 100.0):
        ap.error("--depth must lie in (0, 100] m")
    if not (0.0 < args.height < 0.6 * args.depth):
        ap.error("--height must lie in (0, 0.6 depth): a solitary wave breaks at 0.78 h (McCowan "
                 "1894), and Goring's first-order stroke is meant for waves well below that")
    if not (5.0 <= args.cells <= 200.0):
        ap.error("--cells must lie in [5, 200] points per depth")
    try:
        gauges = [float(v) for v in args.gauges.split(",")]
    except ValueError:
        ap.error("--gauges: %r is not a comma list of numbers (m)" % args.gauges)
    try:
        r = goring_record(args.height, args.depth, gauges, args.cells)
    except ValueError as e:
        ap.error("--gauges: %s" % e)
    if args.json:
        print(json.dumps(r))
        return 0
    print("Goring's wave, H = %g m in h = %g m, under the SGN equations (%g points per depth):" % (
        args.height, args.depth, args.cells))
    for g, a, t, w in zip(gauges, r["amplitude_over_height"], r["crest_times"], r["width_errors"]):
        print("  gauge %6.2f m (%5.1f h): crest %.4f H at %.3f s, width %+.1f %%" % (
            g, g / args.depth, a, t, 100 * w))
    print("lost between the first and last gauge: %.2f %%; celerity %.4f m/s (%+.2f %% of sqrt(g (h + A)))"
          % (100 * r["lost"], r["celerity"], 100 * r["celerity_error"]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
