#!/usr/bin/python3
"""Draws the scale benchmark: datagrams received per round against M (lock-step and real time)
with the data samples a round must deliver (left), and the share of real-time rounds with every input in time with the
lock-step round rate (right), flat against tree. Usage: plot_scale.py scale.csv scale.png"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {"flat": ("tab:red", "o"), "tree": ("tab:blue", "s")}


def number(text: str):
    return float(text) if text else None


def main(csv_path: str, png_path: str) -> None:
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    rate = right.twinx()
    for exchange in sorted({r["exchange"] for r in rows}):
        sel = sorted((r for r in rows if r["exchange"] == exchange), key=lambda r: int(r["stations"]))
        colour, marker = STYLE.get(exchange, ("black", "x"))
        m = [int(r["stations"]) for r in sel]
        counted = [(x, number(r["datagrams_per_round"])) for x, r in zip(m, sel) if r["datagrams_per_round"]]
        if counted:
            left.loglog(*zip(*counted), marker + "-", color=colour, label=f"{exchange}: datagrams received, lock-step")
        at_50hz = [(x, number(r.get("realtime_datagrams_per_round", ""))) for x, r in zip(m, sel)
                   if r.get("realtime_datagrams_per_round")]
        if at_50hz:
            left.loglog(*zip(*at_50hz), marker + "--", color=colour, markerfacecolor="none",
                        label=f"{exchange}: datagrams received, real time at 50 Hz")
        left.loglog(m, [float(r["samples_per_round"]) for r in sel], ":", color=colour,
                    label=f"{exchange}: data samples (formula)")
        in_time = [(x, 100.0 * number(r["realtime_in_time"])) for x, r in zip(m, sel) if r["realtime_in_time"]]
        if in_time:
            right.semilogx(*zip(*in_time), marker + "-", color=colour, label=f"{exchange}: real-time rounds in time")
        rate.loglog(m, [float(r["rounds_per_s"]) for r in sel], marker + "--", color=colour, alpha=0.5,
                    label=f"{exchange}: lock-step rounds/s")
    left.set_xlabel("stations M")
    left.set_ylabel("per round")
    left.set_title("receptions per round")
    left.grid(True, which="both", alpha=0.3)
    left.legend(fontsize=7)
    right.axhline(99.0, color="grey", linestyle=":", label="99 %")
    right.set_xlabel("stations M")
    right.set_ylabel("real-time rounds with every input in time (%)")
    right.set_ylim(0, 102)
    rate.set_ylabel("lock-step rounds/s (dashed)")
    right.set_title("real time at 50 Hz and lock-step rate")
    right.grid(True, which="both", alpha=0.3)
    lines, labels = right.get_legend_handles_labels()
    more_lines, more_labels = rate.get_legend_handles_labels()
    right.legend(lines + more_lines, labels + more_labels, fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(png_path, dpi=110)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_scale.py scale.csv scale.png")
    main(sys.argv[1], sys.argv[2])
