#!/usr/bin/python3
"""Paper 003's figures: one run's 3-D track (its Fig. 1) and the position MSE against time over
the Monte-Carlo runs (its Fig. 2), with the Riccati steady state and the paper's 10 m^2.
Usage: plot_paper003.py mse.csv track.csv out.png steady_sum_m2 steady_per_axis_m2"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main(mse_path, track_path, png_path, steady_sum, steady_axis):
    mse = read(mse_path)
    track = read(track_path)
    fig = plt.figure(figsize=(11, 4.4))
    ax3 = fig.add_subplot(1, 2, 1, projection="3d")
    ax3.plot([float(r["true_x_m"]) for r in track], [float(r["true_y_m"]) for r in track],
             [float(r["true_z_m"]) for r in track], label="truth")
    ax3.plot([float(r["est_x_m"]) for r in track], [float(r["est_y_m"]) for r in track],
             [float(r["est_z_m"]) for r in track], "--", label="Kalman filter")
    ax3.set_xlabel("x (m)")
    ax3.set_ylabel("y (m)")
    ax3.set_zlabel("z (m)")
    ax3.set_title("one run (Fig. 1)")
    ax3.legend(fontsize=8)

    ax = fig.add_subplot(1, 2, 2)
    t = [float(r["t_s"]) for r in mse]
    ax.semilogy(t, [float(r["pos_sum_m2"]) for r in mse], label="position MSE, x+y+z (Eq 11)")
    ax.semilogy(t, [float(r["pos_x_m2"]) for r in mse], label="position MSE, x axis", alpha=0.8)
    ax.axhline(float(steady_sum), color="C0", linestyle=":", label="Riccati steady state, x+y+z")
    ax.axhline(float(steady_axis), color="C1", linestyle=":", label="Riccati steady state, per axis")
    ax.axhline(10.0, color="grey", linestyle="--", label="10 m^2 (paper)")
    ax.axvline(4.0, color="grey", linestyle="-.", alpha=0.5)
    ax.set_xlabel("t (s)")
    ax.set_ylabel("MSE (m^2)")
    ax.set_title("position MSE over Monte-Carlo runs (Fig. 2)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 6:
        sys.exit("usage: plot_paper003.py mse.csv track.csv out.png steady_sum steady_axis")
    main(*sys.argv[1:])
