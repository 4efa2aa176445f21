#!/usr/bin/python3
"""Paper 002's Figs. 3-4: mean error and RMSE of the relative x-position and x-velocity against
time, over the Monte-Carlo runs, for the NCRKF, the nominal KF, the optimal KF and the EKF.
Usage: plot_paper002.py errors.csv out.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FILTERS = [("ncrkf", "NCRKF"), ("nominal_kf", "nominal KF"), ("optimal_kf", "optimal KF"),
           ("ekf", "EKF")]
PANELS = [("mean_x_m", "mean error, x (m)", "linear"), ("rmse_x_m", "RMSE, x (m)", "log"),
          ("mean_vx_mps", "mean error, vx (m/s)", "linear"), ("rmse_vx_mps", "RMSE, vx (m/s)", "log")]


def main(csv_path, png_path):
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))[1:]  # t = 0 is the initial estimate: no log axis there
    t = [float(r["t_s"]) for r in rows]
    fig, axes = plt.subplots(2, 2, figsize=(11, 7), sharex=True)
    for ax, (column, label, scale) in zip(axes.flat, PANELS):
        for key, name in FILTERS:
            ax.plot(t, [float(r[f"{key}_{column}"]) for r in rows], label=name, linewidth=1)
        ax.set_xscale("log")
        ax.set_yscale(scale)
        if scale == "linear":
            values = [abs(float(r[f"{k}_{column}"])) for r in rows[len(rows) // 20:] for k, _ in FILTERS]
            limit = 1.2 * max(values)
            ax.set_ylim(-limit, limit)
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
    for ax in axes[1]:
        ax.set_xlabel("t (s)")
    axes[0][1].legend()
    fig.suptitle("Paper 002: TDOA from a 4-UAV formation, 200 Monte-Carlo runs")
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    main(*sys.argv[1:3])
