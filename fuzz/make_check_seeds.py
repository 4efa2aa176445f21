#!/usr/bin/env python3
"""Writes the seed corpora of the two sample-check targets and their dictionary of special
doubles. The output is committed; run this again only to change the seeds:

    python3 fuzz/make_check_seeds.py

Layouts (see fuzz/fuzz_input.hpp and the targets): every double is 8 bytes, little endian;
a symmetric matrix is its upper triangle, row by row.
  increment_check:   mode byte (even: raw dQ; odd: dQ = G^T G; byte / 2: the registered motion
                     model, 0 = constant_acceleration_3d, N = 9), dQ (45) or G (27), dy (9)
  observation_check: z (3), R upper triangle (6), station position (3)
"""

import math
import struct
from pathlib import Path

HERE = Path(__file__).resolve().parent
DENORM_MIN = 5e-324
NAN = float("nan")
INF = float("inf")


def pack(values):
    return b"".join(struct.pack("<d", v) for v in values)


def upper(m):
    n = len(m)
    return [m[r][c] for r in range(n) for c in range(r, n)]


def jacobian(target, station):
    """d(range, azimuth, elevation)/d(position): the sensor model's analytic form."""
    dx, dy, dz = (t - s for t, s in zip(target, station))
    rho2 = dx * dx + dy * dy
    r2 = rho2 + dz * dz
    r, rho = math.sqrt(r2), math.sqrt(rho2)
    return [
        [dx / r, dy / r, dz / r],
        [-dy / rho2, dx / rho2, 0.0],
        [-dx * dz / (r2 * rho), -dy * dz / (r2 * rho), rho2 / (r2 * rho)],
    ]


def real_increment():
    """dQ = H^T R^-1 H in the 9 x 9 (position block only) and dy = H^T R^-1 H x, for a station
    seeing the default scenario's start point with a zero innovation."""
    target, station, r_diag = (-1200.0, -300.0, 450.0), (100.0, 200.0, 0.0), (1.0, 1e-4, 1e-4)
    h = jacobian(target, station)
    dq = [[0.0] * 9 for _ in range(9)]
    for a in range(3):
        for b in range(3):
            dq[a][b] = sum(h[m][a] * h[m][b] / r_diag[m] for m in range(3))
    hx = [sum(h[m][a] * target[a] for a in range(3)) for m in range(3)]
    dy = [sum(h[m][a] * hx[m] / r_diag[m] for m in range(3)) for a in range(3)] + [0.0] * 6
    return dq, dy


def increment_seeds():
    dq, dy = real_increment()

    def raw(q, y):
        return b"\x00" + pack(upper(q) + y)

    def scaled(q, s):
        return [[v * s for v in row] for row in q]

    def with_entry(q, r, c, value):
        out = [row[:] for row in q]
        out[r][c] = out[c][r] = value
        return out

    zero = [[0.0] * 9 for _ in range(9)]
    # A G with rows of very different size: G^T G rounds to slightly indefinite or not.
    g = [[1e150, 1.0, 1e-150] + [0.0] * 6, [1.0, 1e-8, 0.5] + [0.0] * 6, [3.0] * 9]
    return {
        "real.bin": raw(dq, dy),
        "zero.bin": raw(zero, [0.0] * 9),
        "nan_dq.bin": raw(with_entry(dq, 0, 0, NAN), dy),
        "inf_dy.bin": raw(dq, [INF] + dy[1:]),
        "denormal.bin": raw(scaled(dq, DENORM_MIN), dy),
        "huge.bin": raw(scaled(dq, 1e300), dy),
        "indefinite.bin": raw(scaled(dq, -1.0), dy),
        "gram.bin": b"\x01" + pack(sum(g, []) + dy),
    }


def observation_seeds():
    z = [1500.0, 2.5, 0.3]
    r = [[1.0, 0.0, 0.0], [0.0, 1e-4, 0.0], [0.0, 0.0, 1e-4]]
    position = [100.0, 200.0, 0.0]

    def obs(z_, r_, p_):
        return pack(z_ + upper(r_) + p_)

    return {
        "real.bin": obs(z, r, position),
        "nan_z.bin": obs([NAN, 2.5, 0.3], r, position),
        "r_not_positive.bin": obs(z, [[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]], position),
        "out_of_range.bin": obs([2e6, 2.5, 0.3], r, position),
        "denormal_r.bin": obs(z, [[DENORM_MIN, 0.0, 0.0], [0.0, DENORM_MIN, 0.0],
                                  [0.0, 0.0, DENORM_MIN]], position),
        "far_station.bin": obs(z, r, [1e300, -1e300, 0.0]),
    }


# Values a mutation should be able to drop into any double: the IEEE specials, the edges of
# what the checks accept (pi, pi/2, the range limit, the eigenvalue tolerance).
SPECIALS = {
    "zero": 0.0, "minus_zero": -0.0, "nan": NAN, "inf": INF, "minus_inf": -INF,
    "denorm_min": DENORM_MIN, "normal_min": 2.2250738585072014e-308,
    "max": 1.7976931348623157e308, "one": 1.0, "minus_one": -1.0, "pi": math.pi,
    "half_pi": math.pi / 2, "max_range": 1e6, "tolerance": 1e-9,
}


def main():
    for target, seeds in (("increment_check", increment_seeds()),
                          ("observation_check", observation_seeds())):
        folder = HERE / "corpus" / target
        folder.mkdir(parents=True, exist_ok=True)
        for name, data in seeds.items():
            (folder / name).write_bytes(data)
    lines = ["# Special doubles for the sample-check targets (written by make_check_seeds.py)."]
    for name, value in SPECIALS.items():
        escaped = "".join(f"\\x{b:02x}" for b in struct.pack("<d", value))
        lines.append(f'{name}="{escaped}"')
    (HERE / "doubles.dict").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
