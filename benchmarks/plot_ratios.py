#!/usr/bin/env python3
"""Draws benchmarks/ratios.png from benchmarks/recorded.json.

    python3 benchmarks/plot_ratios.py [--json FILE] [--output FILE]

One horizontal bar per entry of recorded.json's "ratios": CraterKit's speed over the peer's,
drawn from 1x on a logarithmic axis (a bar to the left of the 1x line: the peer is faster), the
range (min-max) as an error bar, and the entry's goal and stretch goal as markers. The figures
are recorded measurements (benchmarks/README.md); this script only draws them.
"""
import argparse
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--json", default=os.path.join(HERE, "recorded.json"))
    ap.add_argument("--output", default=os.path.join(HERE, "ratios.png"))
    args = ap.parse_args()

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with open(args.json, encoding="utf-8") as f:
        entries = json.load(f)["ratios"]
    entries = list(reversed(entries))  # the file's first entry at the top

    fig, ax = plt.subplots(figsize=(9, 4), dpi=100)
    ys = range(len(entries))
    for y, e in zip(ys, entries):
        r = e["ratio"]
        faster = r >= 1.0
        ax.barh(y, r - 1.0, left=1.0, height=0.6,
                color="#4c72b0" if faster else "#c44e52", zorder=2)
        lo, hi = e.get("min"), e.get("max")
        if lo is not None and hi is not None and hi > lo:
            ax.errorbar(r, y, xerr=[[r - lo], [hi - r]], fmt="none", ecolor="black",
                        elinewidth=1, capsize=3, zorder=3)
        if r >= 2.0:  # the figure inside the bar, next to the 1x line
            ax.text(1.05, y, f"{r}×", va="center", fontsize=8, color="white",
                    fontweight="bold", zorder=4)
        else:
            text = f"{r}×" + ("" if faster else f" (peer {1 / r:.1f}× faster)")
            ax.text(max(r, hi or r) * 1.05 if faster else 1.05, y, text, va="center",
                    fontsize=8, zorder=4)
        for key, style in (("goal", "D"), ("stretch_goal", "d")):
            g = e.get(key)
            if g:
                ax.plot(g, y, style, color="#dd8452", markersize=7 if key == "goal" else 6,
                        markerfacecolor="#dd8452" if key == "goal" else "none", zorder=5)

    ax.axvline(1.0, color="black", linewidth=1, zorder=3)
    ax.set_xscale("log")
    ax.set_xlim(0.5, 200)
    ax.set_xticks([0.5, 1, 2, 3, 5, 10, 20, 50, 100])
    ax.set_xticklabels(["0.5×", "1×", "2×", "3×", "5×", "10×", "20×", "50×", "100×"])
    ax.set_yticks(list(ys))
    ax.set_yticklabels([f"{e['label']} ({e['host']}, {e['date'][:10]})" for e in entries],
                       fontsize=8)
    ax.set_xlabel("CraterKit's speed / peer's, same run (log scale; bars: range over rounds or runs)",
                  fontsize=8)
    ax.tick_params(axis="x", labelsize=8)
    ax.grid(axis="x", which="major", color="#dddddd", zorder=0)
    ax.plot([], [], "D", color="#dd8452", label="goal")
    ax.plot([], [], "d", color="#dd8452", markerfacecolor="none", label="stretch goal")
    ax.legend(loc="lower right", fontsize=8, frameon=True)
    fig.suptitle("CraterKit against peer codes: recorded speed ratios on 2 cores "
                 "(hosts N, Q, S as in benchmarks/README.md)", fontsize=9)
    fig.tight_layout()
    fig.savefig(args.output, dpi=100)
    print(args.output)


if __name__ == "__main__":
    main()
