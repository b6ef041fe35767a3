#!/usr/bin/env python3
"""Plots pacifica-accuracy's accuracy.csv: image RMSE vs median ms per setting, log-log, one colour per
model, with each model's Pareto front (the pareto=1 rows) connected. Writes accuracy.png next to the CSV.
Needs matplotlib; without it, prints a message and exits 0 (the benchmark never depends on it).

Usage: python3 tools/bench/plot_accuracy.py OUT_DIR/accuracy.csv
"""
import csv
import os
import sys


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    path = sys.argv[1]
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("plot_accuracy.py: matplotlib is not installed; skipping accuracy.png "
              "(apt-get install python3-matplotlib)")
        return 0
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    fig, ax = plt.subplots(figsize=(8, 5.5))
    models = sorted({r["model"] for r in rows})
    for model in models:
        pts = [r for r in rows if r["model"] == model and float(r["image_rmse"]) > 0.0]
        line = ax.scatter([float(r["ms_median"]) for r in pts], [float(r["image_rmse"]) for r in pts],
                          label=model, s=18)
        for r in pts:
            ax.annotate(f'{r["knob"]}={r["value"]}', (float(r["ms_median"]), float(r["image_rmse"])),
                        fontsize=5, alpha=0.7)
        front = sorted((r for r in pts if r["pareto"] == "1"), key=lambda r: float(r["ms_median"]))
        ax.plot([float(r["ms_median"]) for r in front], [float(r["image_rmse"]) for r in front],
                color=line.get_facecolor()[0], linewidth=1)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(f'median ms per frame ({rows[0]["clock"]})' if rows else "ms")
    ax.set_ylabel("image RMSE vs the model's reference (scene-linear)")
    ax.set_title(f'Pacifica accuracy vs cost — {rows[0]["renderer"]}' if rows else "Pacifica accuracy")
    ax.legend()
    ax.grid(True, which="both", alpha=0.3)
    out = os.path.join(os.path.dirname(os.path.abspath(path)), "accuracy.png")
    fig.savefig(out, dpi=150, bbox_inches="tight")
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
