#!/usr/bin/env python3
"""Spray thrown by a rolling wheel over a wet road: writes scenes/spray.csv for scenes/spray.json.

    python3 scenes/spray.py > scenes/spray.csv          (deterministic: seed 2026)
    python3 scenes/spray.py --count 1000000 --seed 7 > /tmp/spray-1M.csv   (the bench's bigger sprays)

Physics (ground frame, metres, seconds; the car drives along +x, the wheel's centre is at x = 0 now):
- The wheel (radius R) rolls at speed V without slipping. Water carried in the tread leaves it between
  DRAIN_MIN and DRAIN_MAX past the contact patch ("time to drain", Plocher, Browand & Radovich, "Comparing
  spray from tires rolling on a wet surface", Tire Science and Technology 42(3), 2014). A tread point
  at angle θ past the contact moves at (V (1 − cos θ), V sin θ) in the ground frame: each droplet
  leaves with that velocity times a random factor in [0.7, 1] (the sheet slips on the tread), turned
  by up to ±8°, with a sideways velocity of up to ±0.15 V (the sheet spreads).
- Droplets leave at a steady rate over the last EMIT_S seconds; each flies ballistically under gravity
  and quadratic air drag, a = g − (3 ρ_air C_d / (4 ρ_water d)) |u| u (sphere, C_d = 0.47, still air),
  integrated by midpoint steps of 0.5 ms. Droplets that reach the road are gone (they splash).
- Sizes: the USC tire-spray measurements (Plocher et al.: a groove's water sheet at Weber number 2700,
  about this wheel's 6 m/s) found diameters from 80 µm to 9 mm with a mean near 0.8 mm. Here diameters
  follow a Rosin–Rammler distribution, F(d) = 1 − exp(−(d/X)^q) (Rosin & Rammler, J. Inst. Fuel 7, 1933,
  the usual law for sprays: Lefebvre, Atomization and Sprays, 1989), with q = 2 (our choice: the
  measurements give the range and mean, not the shape) and X set so the mean is 0.8 mm, truncated to
  the measured range.
Output: CSV "x,y,z,r" (centre and radius, metres), one droplet a row.
"""
import argparse
import math
import random
import sys

R = 0.30                 # wheel radius (m)
V = 6.0                  # speed (m/s)
DRAIN_MIN, DRAIN_MAX = math.radians(20), math.radians(80)
EMIT_S = 0.15            # seconds of spray in the air
G = 9.81
RHO_AIR, RHO_WATER, CD = 1.2, 1000.0, 0.47
MEAN_D, Q = 0.8e-3, 2.0
D_MIN, D_MAX = 80e-6, 9e-3
X = MEAN_D / math.gamma(1 + 1 / Q)   # Rosin–Rammler scale for that mean
DT = 0.5e-3
TREAD_HALF_WIDTH = 0.09  # the tire's half width (m): droplets leave across it


def diameter(rng):
    while True:
        d = X * (-math.log(1 - rng.random())) ** (1 / Q)
        if D_MIN <= d <= D_MAX:
            return d


def fly(p, u, d, t):
    """Midpoint steps for t seconds; None if the droplet reaches the road."""
    k = 3 * RHO_AIR * CD / (4 * RHO_WATER * d)
    r = d / 2

    def acc(u):
        s = math.sqrt(u[0] ** 2 + u[1] ** 2 + u[2] ** 2)
        return (-k * s * u[0], -G - k * s * u[1], -k * s * u[2])

    steps = int(t / DT)
    h = t / steps if steps else 0
    for _ in range(steps):
        a = acc(u)
        um = [u[i] + 0.5 * h * a[i] for i in range(3)]
        am = acc(um)
        p = [p[i] + h * um[i] for i in range(3)]
        u = [u[i] + h * am[i] for i in range(3)]
        if p[1] < r:
            return None
    return p


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--count", type=int, default=12000, help="droplets in the air (default 12000)")
    ap.add_argument("--seed", type=int, default=2026)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    out = sys.stdout
    out.write("x,y,z,r\n")
    n = 0
    while n < args.count:
        age = rng.random() * EMIT_S
        theta = rng.uniform(DRAIN_MIN, DRAIN_MAX)
        # where the tread point was when it let go: the wheel's centre was at x = −V·age
        p = [-V * age - R * math.sin(theta), R - R * math.cos(theta), rng.uniform(-TREAD_HALF_WIDTH, TREAD_HALF_WIDTH)]
        f = rng.uniform(0.7, 1.0)
        turn = math.radians(rng.uniform(-8, 8))
        ux, uy = V * (1 - math.cos(theta)) * f, V * math.sin(theta) * f
        u = [ux * math.cos(turn) - uy * math.sin(turn), ux * math.sin(turn) + uy * math.cos(turn),
             rng.uniform(-0.15, 0.15) * V]
        d = diameter(rng)
        q = fly(p, u, d, age)
        if q is None:
            continue
        out.write("%.4f,%.4f,%.4f,%.3e\n" % (q[0], q[1], q[2], d / 2))
        n += 1


if __name__ == "__main__":
    main()
