#!/usr/bin/python3
"""Plots RMSE against the number of stations, one line per speed and architecture, in the
manner of paper 000's Figure 1. Usage: plot_sweep.py sweep.csv sweep.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path: str, png_path: str) -> None:
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    speeds = sorted({float(r["speed_kmh"]) for r in rows})
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for speed in speeds:
        sel = sorted((r for r in rows if float(r["speed_kmh"]) == speed), key=lambda r: int(r["stations"]))
        m = [int(r["stations"]) for r in sel]
        ax.semilogy(m, [float(r["rmse_central_m"]) for r in sel], "o-", label=f"central, {speed:.0f} km/h")
        ax.semilogy(m, [float(r["rmse_p2p_m"]) for r in sel], "x--", label=f"peer-to-peer, {speed:.0f} km/h")
    ax.axhline(0.3, color="grey", linestyle=":", label="0.3 m (paper's claim for M >= 3)")
    ax.set_xlabel("number of stations M")
    ax.set_ylabel("position RMSE (m)")
    runs = rows[0]["runs"] if rows else "?"
    ax.set_title(f"RMSE vs number of stations ({runs} Monte-Carlo runs)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_sweep.py sweep.csv sweep.png")
    main(sys.argv[1], sys.argv[2])
