#!/usr/bin/env python3
"""scripts/study_plot.py DIR — the plots of `softmol study`: for each DIR/<method>.csv, a PNG
DIR/<method>.png of error against cost (setup + frame ms, log scale) with the Pareto front
joined and marked and the shipped default circled. The front is the study's own (column
`front`), not recomputed here. Needs python3-matplotlib (Debian); exits 1 with a message when
it is missing or a CSV lacks a column below."""
import csv
import pathlib
import sys

# The columns read here; cli/study.h kPlotColumns lists the same names (a test compares them).
COLUMNS = ("method", "label", "cost_ms", "error", "error_name", "default", "front")


def read_rows(path):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        missing = [c for c in COLUMNS if c not in (reader.fieldnames or [])]
        if missing:
            sys.exit(f"study_plot: {path}: no column {', '.join(missing)}")
        return list(reader)


def plot(path, rows, plt, ticker):
    cost = [max(float(r["cost_ms"]), 1e-3) for r in rows]  # log axis: no zero
    error = [float(r["error"]) for r in rows]
    fig, ax = plt.subplots(figsize=(6.4, 4.2), dpi=80)
    ax.scatter(cost, error, s=14, color="0.55", label="sweep point")
    front = sorted((c, e, r["label"]) for c, e, r in zip(cost, error, rows) if r["front"] == "1")
    if front:
        ax.plot([p[0] for p in front], [p[1] for p in front], "-o", color="tab:blue", ms=4, lw=1.2,
                label="Pareto front")
        for c, e, label in front:
            ax.annotate(label, (c, e), fontsize=6, xytext=(3, 3), textcoords="offset points")
    for c, e, r in zip(cost, error, rows):
        if r["default"] == "1":
            ax.scatter([c], [e], s=160, facecolors="none", edgecolors="tab:red", linewidths=1.5,
                       label="shipped default")
    ax.set_xscale("log")
    plain = ticker.FuncFormatter(lambda v, _: f"{v:g}")  # 2, 5, 10 rather than 2x10^0
    ax.xaxis.set_major_formatter(plain)
    ax.xaxis.set_minor_formatter(plain if max(cost) / min(cost) < 20 else ticker.NullFormatter())
    ax.tick_params(axis="x", which="minor", labelsize=6)
    ax.set_xlabel("cost per frame, ms (setup + frame)")
    ax.set_ylabel(rows[0]["error_name"] if len(rows[0]["error_name"]) < 60 else "error")
    ax.set_title(f"{rows[0]['method']}: {rows[0]['error_name']}"[:90], fontsize=8)
    ax.grid(True, which="both", lw=0.3, color="0.85")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path.with_suffix(".png"))
    plt.close(fig)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: study_plot.py DIR")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib import ticker
    except ImportError:
        sys.exit("study_plot: matplotlib is missing (apt-get install python3-matplotlib)")
    csvs = sorted(pathlib.Path(sys.argv[1]).glob("*.csv"))
    if not csvs:
        sys.exit(f"study_plot: no CSV in {sys.argv[1]}")
    for path in csvs:
        rows = read_rows(path)
        if rows:
            plot(path, rows, plt, ticker)


if __name__ == "__main__":
    main()
