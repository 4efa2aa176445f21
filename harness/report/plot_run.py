#!/usr/bin/python3
"""One or more DDS runs: the position error of the central and the peer-to-peer track (1 s
rolling RMS) and the distance between the two. Usage: plot_run.py out.png steps.csv [...]"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rolling_rms(values, window):
    out, acc = [], 0.0
    squares = [v * v for v in values]
    for i, s in enumerate(squares):
        acc += s
        if i >= window:
            acc -= squares[i - window]
        out.append(math.sqrt(acc / min(i + 1, window)))
    return out


def main(png_path, step_files):
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.0, 6.0), sharex=True)
    for path in step_files:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        label = os.path.basename(os.path.dirname(os.path.abspath(path)))
        t = [float(r["time_s"]) for r in rows]
        dt = t[1] - t[0] if len(t) > 1 else 1.0
        window = max(1, round(1.0 / dt))
        top.plot(t, rolling_rms([float(r["error_central_m"]) for r in rows], window), "-", lw=1.2,
                 label=f"central, {label}")
        top.plot(t, rolling_rms([float(r["error_p2p_m"]) for r in rows], window), "--", lw=1.2,
                 label=f"peer-to-peer, {label}")
        bottom.semilogy(t, [max(float(r["central_minus_p2p_m"]), 1e-16) for r in rows], lw=0.8,
                        label=label)
    top.axhline(0.3, color="grey", linestyle=":", label="0.3 m (paper's bound)")
    top.set_ylabel("position error, 1 s RMS (m)")
    top.set_title("DDS run: central vs peer-to-peer track")
    top.grid(True, alpha=0.3)
    top.legend(fontsize=8)
    bottom.set_ylabel("|central - peer-to-peer| (m)")
    bottom.set_xlabel("time (s)")
    bottom.grid(True, which="both", alpha=0.3)
    bottom.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit("usage: plot_run.py out.png steps.csv [steps.csv ...]")
    main(sys.argv[1], sys.argv[2:])
