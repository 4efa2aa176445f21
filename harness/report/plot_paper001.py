#!/usr/bin/python3
"""Paper 001's figures: one typical test path with every filter's track (its Fig. 8), each
filter's position error along it, and the distribution of per-path RMSE over the test paths
(its Table 3 as a picture).
Usage: plot_paper001.py track.csv rmse.csv out.png"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main(track_path, rmse_path, png_path):
    track = read(track_path)
    rmse = read(rmse_path)
    filters = [c[:-2] for c in track[0].keys() if c.endswith(" x")]
    fig, (ax_track, ax_error, ax_rmse) = plt.subplots(1, 3, figsize=(16, 5))
    true_x = [float(r["true_x_m"]) for r in track]
    true_y = [float(r["true_y_m"]) for r in track]
    ax_track.plot(true_x, true_y, "k-", linewidth=2.5, label="truth")
    for name in filters:
        xs = [float(r[name + " x"]) for r in track]
        ys = [float(r[name + " y"]) for r in track]
        ax_track.plot(xs, ys, linewidth=1, label=name)
        errors = [math.hypot(x - tx, y - ty) for x, y, tx, ty in zip(xs, ys, true_x, true_y)]
        ax_error.plot([0.1 * int(r["step"]) for r in track], errors, linewidth=1, label=name)
    pad = 20.0
    ax_track.set_xlim(min(true_x) - pad, max(true_x) + pad)
    ax_track.set_ylim(min(true_y) - pad, max(true_y) + pad)
    ax_track.set_xlabel("x (m)")
    ax_track.set_ylabel("y (m)")
    ax_track.set_aspect("equal", adjustable="datalim")
    ax_track.set_title("a typical test path (the IMM's median RMSE)")
    ax_track.legend(fontsize=8)
    ax_error.set_xlabel("t (s)")
    ax_error.set_ylabel("position error (m)")
    ax_error.set_ylim(0, 12)
    ax_error.set_title("error along that path")

    names = [c for c in rmse[0].keys() if c != "path"]
    ax_rmse.boxplot([[float(r[n]) for r in rmse] for n in names], labels=names, showfliers=False)
    ax_rmse.set_ylabel("per-path RMSE per axis (m)")
    ax_rmse.set_title(f"{len(rmse)} test paths")
    ax_rmse.tick_params(axis="x", labelsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=100)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
