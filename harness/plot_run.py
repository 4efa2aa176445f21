#!/usr/bin/python3
"""Position error against time for the central and the peer-to-peer track of one or more DDS
runs. Usage: plot_run.py out.png steps.csv [steps.csv ...] (one run per steps.csv)."""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(png_path: str, step_files: list) -> None:
    fig, ax = plt.subplots(figsize=(7.0, 4.2))
    for path in step_files:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        label = os.path.basename(os.path.dirname(os.path.abspath(path)))
        t = [float(r["time_s"]) for r in rows]
        ax.semilogy(t, [float(r["error_central_m"]) for r in rows], "-", lw=0.8, label=f"central, {label}")
        ax.semilogy(t, [float(r["error_p2p_m"]) for r in rows], "--", lw=0.8, label=f"peer-to-peer, {label}")
    ax.axhline(0.3, color="grey", linestyle=":", label="0.3 m")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("position error (m)")
    ax.set_title("DDS run: central and peer-to-peer tracks")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png_path, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit("usage: plot_run.py out.png steps.csv [steps.csv ...]")
    main(sys.argv[1], sys.argv[2:])
