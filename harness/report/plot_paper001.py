#!/usr/bin/python3
"""Paper 001's figures: one test path with every filter's track (its Fig. 8) and the
distribution of per-path RMSE over the test paths (its Table 3 as a picture).
Usage: plot_paper001.py track.csv rmse.csv out.png"""
import csv
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
    fig, (ax_track, ax_rmse) = plt.subplots(1, 2, figsize=(12, 5))
    ax_track.plot([float(r["true_x_m"]) for r in track], [float(r["true_y_m"]) for r in track],
                  "k-", linewidth=2.5, label="truth")
    for name in filters:
        ax_track.plot([float(r[name + " x"]) for r in track],
                      [float(r[name + " y"]) for r in track], linewidth=1, label=name)
    ax_track.set_xlabel("x (m)")
    ax_track.set_ylabel("y (m)")
    ax_track.set_aspect("equal", adjustable="datalim")
    ax_track.set_title("one test path")
    ax_track.legend(fontsize=8)

    names = [c for c in rmse[0].keys() if c != "path"]
    ax_rmse.boxplot([[float(r[n]) for r in rmse] for n in names], labels=names, showfliers=False)
    ax_rmse.set_ylabel("per-path RMSE (m)")
    ax_rmse.set_title(f"{len(rmse)} test paths")
    ax_rmse.tick_params(axis="x", labelsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
