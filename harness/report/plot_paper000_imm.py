#!/usr/bin/python3
"""The station network's IMM against the CA filter on paper 000's 300 km/h run: position RMSE,
ANEES and the IMM's mode probabilities against time, the turn (10-18 s) and climb shaded.
Usage: plot_paper000_imm.py imm_turn.csv out.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(csv_path, png_path):
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    t = [float(r["t_s"]) for r in rows]
    fig, axes = plt.subplots(3, 1, figsize=(9, 8), sharex=True)
    for ax in axes:
        ax.axvspan(10, 18, color="0.9")
        ax.axvspan(30, 34, color="0.95")
    axes[0].plot(t, [float(r["rmse_ca_m"]) for r in rows], label="CA filter (paper)")
    axes[0].plot(t, [float(r["rmse_imm_m"]) for r in rows], label="IMM CV+CA+CT")
    axes[0].set_ylabel("position RMSE (m)")
    axes[0].legend()
    axes[1].plot(t, [float(r["anees_ca"]) for r in rows], label="CA filter")
    axes[1].plot(t, [float(r["anees_imm"]) for r in rows], label="IMM")
    axes[1].axhline(6, color="k", linewidth=0.8, linestyle="--", label="6 (consistent)")
    axes[1].set_ylabel("ANEES of [p; v]")
    axes[1].legend()
    for name, column in (("CV", "mu_cv"), ("CA", "mu_ca"), ("CT", "mu_ct")):
        axes[2].plot(t, [float(r[column]) for r in rows], label=name)
    axes[2].set_ylabel("mode probability")
    axes[2].set_xlabel("t (s); turn 10-18 s, climb 30-34 s")
    axes[2].legend()
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
