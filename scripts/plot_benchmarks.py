#!/usr/bin/env python3
"""Plots of the benchmarks' CSV files as SVG (Python 3 standard library only, no matplotlib).

Usage:
    python3 scripts/plot_benchmarks.py [RESULTS_DIR] [OUT_DIR]

RESULTS_DIR holds one machine's results as the benchmarks write them (samples/bench/results/<machine>/,
samples/bench/results/README.md; default: samples/bench/results/vm-2core, the runs the documents
quote); OUT_DIR receives the SVG files (default docs/img). Written, from the files present:
    bench_queries_pareto.svg  time per query against the effective maximum separation error, log-log,
                              one panel each for all pose pairs, smooth pairs and rough pairs
                              (bench_queries.csv, _smooth.csv, _rough.csv)
    bench_queries_sweep.svg   box tests, segment pairs and time per query against the segment count
                              (one contact) and against the contact count (1024 segments)
                              (bench_queries_sweep.csv)
    bench_box2d_scenes.svg    ms per step of the four variants (bridge auto / finest level, polygon
                              compounds, native circles) against the body count (S = 64) and against
                              the segment count (N = 256), log-log (bench_box2d_scenes.csv, and the
                              largest sizes from bench_box2d_scenes_large.csv when that run was separate)
    bench_hard_cases.svg      µs per query against the resolution δ / size (1e-2 ... 1e-9), one line per hard
                              case at the origin (1e6 away dashed), with a δ^-1/2 reference line
                              (bench_hard_cases.csv)
A configuration with a missed or spurious contact is drawn hollow at an error of at least D = 0.005
(the benchmark's contact window), as the benchmark's summary counts it.
"""

import argparse
import csv
import math
import os
import sys

WINDOW = 0.005  # D of bench_queries.cpp
FLOOR = 1e-17   # errors of 0 are drawn here

COLOURS = {
    "rugo": "#1f6fb4",
    "brute": "#7b3fa0",
    "box2d": "#d0502a",
    "box2d_narrow": "#e8a33d",
}
LABELS = {
    "rugo": "librugo (level 0, -1, -2, -3)",
    "brute": "librugo narrow phase, all segment pairs",
    "box2d": "Box2D polygons (m vertices)",
    "box2d_narrow": "Box2D polygons, b2CollidePolygons only",
}


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def eff_err(row):
    e = float(row["max_sep_err"])
    if int(row["missed"]) + int(row["spurious"]) > 0:
        e = max(e, WINDOW)
    return max(e, FLOOR)


class Panel:
    """A log-log (or log-linear) plot area inside an SVG document."""

    def __init__(self, x, y, w, h, xlim, ylim, xlog=True, ylog=True):
        self.x, self.y, self.w, self.h = x, y, w, h
        self.xlim, self.ylim, self.xlog, self.ylog = xlim, ylim, xlog, ylog
        self.out = []

    def _t(self, v, lim, log):
        lo, hi = lim
        if log:
            v, lo, hi = math.log10(v), math.log10(lo), math.log10(hi)
        return (v - lo) / (hi - lo)

    def px(self, v):
        return self.x + self.w * self._t(v, self.xlim, self.xlog)

    def py(self, v):
        return self.y + self.h * (1.0 - self._t(v, self.ylim, self.ylog))

    def text(self, x, y, s, size=11, anchor="start", rotate=None, weight="normal", colour="#222"):
        tr = f' transform="rotate({rotate} {x:.1f} {y:.1f})"' if rotate is not None else ""
        s = s.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
        self.out.append(f'<text x="{x:.1f}" y="{y:.1f}" font-size="{size}" text-anchor="{anchor}" '
                        f'font-weight="{weight}" fill="{colour}"{tr}>{s}</text>')

    def frame(self, title, xlabel, ylabel, xticks, yticks):
        o = self.out
        o.append(f'<rect x="{self.x}" y="{self.y}" width="{self.w}" height="{self.h}" fill="white" stroke="#444"/>')
        for v, lab in xticks:
            X = self.px(v)
            o.append(f'<line x1="{X:.1f}" y1="{self.y}" x2="{X:.1f}" y2="{self.y + self.h}" stroke="#e4e4e4"/>')
            self.text(X, self.y + self.h + 14, lab, 10, "middle")
        for v, lab in yticks:
            Y = self.py(v)
            o.append(f'<line x1="{self.x}" y1="{Y:.1f}" x2="{self.x + self.w}" y2="{Y:.1f}" stroke="#e4e4e4"/>')
            self.text(self.x - 5, Y + 3.5, lab, 10, "end")
        self.text(self.x + self.w / 2, self.y - 8, title, 12, "middle", weight="bold")
        self.text(self.x + self.w / 2, self.y + self.h + 30, xlabel, 11, "middle")
        self.text(self.x - 48, self.y + self.h / 2, ylabel, 11, "middle", rotate=-90)

    def hline(self, v, colour, label):
        Y = self.py(v)
        self.out.append(f'<line x1="{self.x}" y1="{Y:.1f}" x2="{self.x + self.w}" y2="{Y:.1f}" stroke="{colour}" '
                        f'stroke-dasharray="2,3"/>')
        self.text(self.x + self.w - 4, Y - 3, label, 9, "end", colour=colour)

    def series(self, pts, colour, dashed=False, labels=None, hollow=None, marker="circle"):
        if not pts:
            return
        d = " ".join(f"{'M' if i == 0 else 'L'}{self.px(x):.1f},{self.py(y):.1f}" for i, (x, y) in enumerate(pts))
        dash = ' stroke-dasharray="5,3"' if dashed else ""
        self.out.append(f'<path d="{d}" fill="none" stroke="{colour}" stroke-width="1.6"{dash}/>')
        for i, (x, y) in enumerate(pts):
            X, Y = self.px(x), self.py(y)
            fill = "white" if hollow and hollow[i] else colour
            if marker == "square":
                self.out.append(f'<rect x="{X - 3.2:.1f}" y="{Y - 3.2:.1f}" width="6.4" height="6.4" fill="{fill}" '
                                f'stroke="{colour}" stroke-width="1.3"/>')
            else:
                self.out.append(f'<circle cx="{X:.1f}" cy="{Y:.1f}" r="3.4" fill="{fill}" stroke="{colour}" '
                                f'stroke-width="1.3"/>')
            if labels:
                self.text(X + 5, Y - 5, labels[i], 9, colour=colour)


def decade_ticks(lo, hi, every=1):
    ticks = []
    e = math.floor(math.log10(lo))
    while 10.0 ** e <= hi * 1.0001:
        if 10.0 ** e >= lo * 0.9999 and e % every == 0:
            ticks.append((10.0 ** e, f"1e{e}" if abs(e) > 2 else f"{10.0 ** e:g}"))
        e += 1
    return ticks


def svg_doc(width, height, body):
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
            f'viewBox="0 0 {width} {height}" font-family="Helvetica, Arial, sans-serif">\n'
            f'<rect width="{width}" height="{height}" fill="white"/>\n' + "\n".join(body) + "\n</svg>\n")


def pareto_plot(csv_dir, out_path):
    subsets = [("all pose pairs", "bench_queries.csv"), ("smooth pairs", "bench_queries_smooth.csv"),
               ("rough pairs", "bench_queries_rough.csv")]
    data = []
    for title, name in subsets:
        path = os.path.join(csv_dir, name)
        if os.path.exists(path):
            data.append((title, read_csv(path)))
    xs = [eff_err(r) for _, rows in data for r in rows]
    ys = [float(r["time_ns_per_query"]) / 1000.0 for _, rows in data for r in rows]
    xlim = (10.0 ** math.floor(math.log10(min(xs))), 10.0 ** math.ceil(math.log10(max(xs))))
    ylim = (10.0 ** math.floor(math.log10(min(ys))), 10.0 ** math.ceil(math.log10(max(ys))))
    W, H, left, top, gap = 330, 300, 70, 40, 75
    body = []
    for k, (title, rows) in enumerate(data):
        p = Panel(left + k * (W + gap), top, W, H, xlim, ylim)
        p.frame(title, "max separation error (body size 1)", "time per query [µs]",
                decade_ticks(*xlim, every=2), decade_ticks(*ylim))
        p.hline(1.0, "#999", "")
        for meth in ["box2d_narrow", "box2d", "brute", "rugo"]:
            rs = [r for r in rows if r["method"] == meth]
            if not rs:
                continue
            if meth == "rugo":
                rs.sort(key=lambda r: -int(r["param"]))
            else:
                rs.sort(key=lambda r: int(r["param"]))
            pts = [(eff_err(r), float(r["time_ns_per_query"]) / 1000.0) for r in rs]
            hollow = [int(r["missed"]) + int(r["spurious"]) > 0 for r in rs]
            if meth == "rugo":
                labels = ["L" + r["param"] for r in rs]
            elif meth == "box2d":
                labels = [r["param"] for r in rs]
            else:
                labels = None
            p.series(pts, COLOURS[meth], dashed=(meth == "box2d_narrow"), labels=labels, hollow=hollow,
                     marker="square" if meth.startswith("box2d") else "circle")
        # the goal targets
        for e, lab in [(1e-3, "1e-3"), (1e-5, "1e-5")]:
            X = p.px(e)
            p.out.append(f'<line x1="{X:.1f}" y1="{p.y}" x2="{X:.1f}" y2="{p.y + p.h}" stroke="#2a9d55" '
                         f'stroke-dasharray="3,3"/>')
            p.text(X + 3, p.y + p.h - 6, lab, 9, colour="#2a9d55")
        body += p.out
    # legend
    ly = top + H + 52
    lx = left
    for meth in ["rugo", "brute", "box2d", "box2d_narrow"]:
        c = COLOURS[meth]
        dash = ' stroke-dasharray="5,3"' if meth == "box2d_narrow" else ""
        body.append(f'<line x1="{lx}" y1="{ly}" x2="{lx + 24}" y2="{ly}" stroke="{c}" stroke-width="1.6"{dash}/>')
        body.append(f'<text x="{lx + 30}" y="{ly + 4}" font-size="11" fill="#222">{LABELS[meth]}</text>')
        lx += 265
    body.append(f'<text x="{left}" y="{ly + 22}" font-size="10" fill="#555">Hollow: a missed or spurious contact '
                f'(drawn at an error of at least D = {WINDOW}). Green: the goals\' error levels. Lower left is better.'
                f'</text>')
    width = left + len(data) * (W + gap)
    with open(out_path, "w") as f:
        f.write(svg_doc(width, ly + 36, body))


def sweep_plot(csv_dir, out_path):
    rows = read_csv(os.path.join(csv_dir, "bench_queries_sweep.csv"))
    seg = [r for r in rows if r["kind"] == "segments"]
    con = [r for r in rows if r["kind"] == "contacts"]
    W, H, left, top, gap = 330, 240, 70, 40, 80
    body = []
    colours = {"ellipse-ellipse": "#1f6fb4", "bean-bean": "#2a9d55", "comb-slab": "#d0502a"}

    def counts_panel(x, rs, key, xlabel, title, xlog_ticks):
        xs = [float(r[key]) for r in rs]
        vals = [float(r[c]) for r in rs for c in ("box_tests", "segment_pairs")]
        xlim = (min(xs) / 1.3, max(xs) * 1.3)
        ylim = (10.0 ** math.floor(math.log10(min(vals))), 10.0 ** math.ceil(math.log10(max(vals) * 3)))
        p = Panel(x, top, W, H, xlim, ylim)
        p.frame(title, xlabel, "count per query", xlog_ticks, decade_ticks(*ylim))
        for i, shapes in enumerate(sorted({r["shapes"] for r in rs})):
            sr = sorted([r for r in rs if r["shapes"] == shapes], key=lambda r: float(r[key]))
            c = colours.get(shapes, "#444")
            p.series([(float(r[key]), float(r["box_tests"])) for r in sr], c)
            p.series([(float(r[key]), float(r["segment_pairs"])) for r in sr], c, dashed=True, marker="square")
            last = sr[-1]
            p.text(p.px(float(last[key])) - 4, p.py(float(last["box_tests"])) - 8 - 12 * i, shapes + ": boxes", 9, "end",
                   colour=c)
            p.text(p.px(float(last[key])) - 4, p.py(float(last["segment_pairs"])) + 14 + 12 * i, shapes + ": pairs", 9,
                   "end", colour=c)
        # what proportional growth would look like, from the first box count
        first = sorted(rs, key=lambda r: float(r[key]))[0]
        x0, y0 = float(first[key]), float(first["box_tests"])
        x1 = max(xs)
        y1 = y0 * x1 / x0
        if y1 > ylim[1]:
            x1 = x0 * ylim[1] / y0
            y1 = ylim[1]
        p.out.append(f'<line x1="{p.px(x0):.1f}" y1="{p.py(y0):.1f}" x2="{p.px(x1):.1f}" y2="{p.py(y1):.1f}" '
                     f'stroke="#999" stroke-dasharray="2,3"/>')
        p.text(p.px(x1) - 4, p.py(y1) + 12, "∝ " + ("segments" if key == "segments" else "contacts"), 9, "end",
               colour="#777")
        return p

    def time_panel(x, y, rs, key, xlabel, xlog_ticks):
        xs = [float(r[key]) for r in rs]
        ts = [float(r["time_ns_per_query"]) / 1000.0 for r in rs]
        xlim = (min(xs) / 1.3, max(xs) * 1.3)
        ylim = (10.0 ** math.floor(math.log10(min(ts))), 10.0 ** math.ceil(math.log10(max(ts))))
        p = Panel(x, y, W, H * 0.75, xlim, ylim)
        p.frame("", xlabel, "time per query [µs]", xlog_ticks, decade_ticks(*ylim))
        for i, shapes in enumerate(sorted({r["shapes"] for r in rs})):
            sr = sorted([r for r in rs if r["shapes"] == shapes], key=lambda r: float(r[key]))
            c = colours.get(shapes, "#444")
            p.series([(float(r[key]), float(r["time_ns_per_query"]) / 1000.0) for r in sr], c)
            p.text(p.x + 6, p.y + 14 + 12 * i, shapes, 9, colour=c)
        return p

    nt = [(float(v), str(v)) for v in sorted({int(r["segments"]) for r in seg})]
    kt = [(float(v), str(v)) for v in sorted({int(r["contacts"]) for r in con})]
    body += counts_panel(left, seg, "segments", "segments per shape", "one contact, 32 ... 4096 segments", nt).out
    body += counts_panel(left + W + gap, con, "contacts", "contacts (comb on slabs, 1024 segments)",
                         "1024 segments, 1 ... 32 contacts", kt).out
    ty = top + H + 60
    body += time_panel(left, ty, seg, "segments", "segments per shape", nt).out
    body += time_panel(left + W + gap, ty, con, "contacts", "contacts", kt).out
    ly = ty + H * 0.75 + 52
    body.append(f'<text x="{left}" y="{ly}" font-size="10" fill="#555">Solid: OBB tests of the tree traversal; '
                f'dashed: segment pairs given to the narrow phase. Finest level, gap 1e-7, margin 2e-7.</text>')
    with open(out_path, "w") as f:
        f.write(svg_doc(left + 2 * (W + gap), ly + 16, body))


B2_VARIANTS = [("bridge_auto", "#1f6fb4", "bridge, automatic level of detail"),
               ("bridge_finest", "#7b3fa0", "bridge, finest level"),
               ("polygon", "#d0502a", "Box2D convex-polygon compounds (same 5 mm error)"),
               ("circle", "#2a9d55", "native b2CircleShape (floor)")]


def box2d_scenes_plot(csv_paths, out_path):
    """csv_paths: the runs to draw, the first one's row winning for a (variant, N, S) in several."""
    rows, seen = [], set()
    for path in csv_paths:
        for r in read_csv_comments(path):
            key = (r.get("variant"), r.get("N"), r.get("S"))
            if key[0] in {v for v, _, _ in B2_VARIANTS} and key not in seen:
                seen.add(key)
                rows.append(r)
    W, H, left, top, gap = 360, 280, 70, 40, 80
    body = []
    ms = [float(r["ms_per_step"]) for r in rows]
    ylim = (10.0 ** math.floor(math.log10(min(ms))), 10.0 ** math.ceil(math.log10(max(ms))))
    sweeps = [("N", "S", 64, "bodies N (S = 64 segments)", "N bodies, S = 64"),
              ("S", "N", 256, "segments per body S (N = 256)", "N = 256 bodies, S segments")]
    for k, (key, fixed, value, xlabel, title) in enumerate(sweeps):
        rs = [r for r in rows if int(r[fixed]) == value]
        if not rs:
            continue
        xs = sorted({int(r[key]) for r in rs})
        xlim = (xs[0] / 1.5, xs[-1] * 1.5)
        p = Panel(left + k * (W + gap), top, W, H, xlim, ylim)
        p.frame(title, xlabel, "CPU ms per step", [(float(x), str(x)) for x in xs], decade_ticks(*ylim))
        for v, colour, _ in B2_VARIANTS:
            sr = sorted([r for r in rs if r["variant"] == v], key=lambda r: int(r[key]))
            p.series([(float(r[key]), float(r["ms_per_step"])) for r in sr], colour,
                     dashed=(v == "bridge_finest"), marker="square" if v in ("polygon", "circle") else "circle")
        body += p.out
    ly = top + H + 52
    lx = left
    for i, (v, colour, label) in enumerate(B2_VARIANTS):
        x = lx + (i % 2) * 400
        y = ly + (i // 2) * 18
        dash = ' stroke-dasharray="5,3"' if v == "bridge_finest" else ""
        body.append(f'<line x1="{x}" y1="{y}" x2="{x + 24}" y2="{y}" stroke="{colour}" stroke-width="1.6"{dash}/>')
        body.append(f'<text x="{x + 30}" y="{y + 4}" font-size="11" fill="#222">{label}</text>')
    note_y = ly + 44
    body.append(f'<text x="{left}" y="{note_y}" font-size="10" fill="#555">Bodies falling and settling in a container '
                f'at 60 Hz, 8/3 iterations; thread CPU time per step after the warm-up. Lower is better.</text>')
    body.append(f'<text x="{left}" y="{note_y + 14}" font-size="10" fill="#555">N = 1024 and S = 512 ran fewer steps '
                f'(see the CSV): their falling phase weighs more.</text>')
    with open(out_path, "w") as f:
        f.write(svg_doc(left + 2 * (W + gap), note_y + 30, body))


HARD_COLOURS = ["#1f6fb4", "#d0502a", "#2a9d50", "#7b3fa0", "#e8a33d", "#17a2b8", "#8c564b", "#555555"]


def hard_cases_plot(csv_path, out_path):
    """bench_hard_cases: cost against the resolution, with a delta^-1/2 line through the cheapest case at 1e-2."""
    rows = [r for r in read_csv(csv_path) if float(r["delta_rel"]) > 0]
    cases = []
    for r in rows:
        if r["case"] not in cases:
            cases.append(r["case"])
    us = [float(r["us_median"]) for r in rows]
    xlim = (1e-9 / 2, 1e-2 * 2)
    ylim = (10.0 ** math.floor(math.log10(min(us))), 10.0 ** math.ceil(math.log10(max(us))))
    W, H = 760, 520
    # the x axis runs from coarse (left) to fine (right)
    p = Panel(90, 40, 430, 420, (xlim[1], xlim[0]), ylim)
    p.frame("Hard cases: cost against the resolution", "resolution δ / size (finer to the right)",
            "µs per query (median)", [(10.0 ** e, f"1e{e}") for e in range(-9, -1)], decade_ticks(ylim[0], ylim[1]))
    for i, c in enumerate(cases):
        col = HARD_COLOURS[i % len(HARD_COLOURS)]
        for far in ("0", "1"):
            pts = sorted(((float(r["delta_rel"]), float(r["us_median"])) for r in rows
                          if r["case"] == c and r["far"] == far), reverse=True)
            p.series(pts, col, dashed=(far == "1"))
        p.text(540, 60 + 18 * i, c, 11, colour=col)
    base = min(float(r["us_median"]) for r in rows if float(r["delta_rel"]) == 1e-2)
    ref = [(d, base * (d / 1e-2) ** -0.5) for d in (1e-2, 1e-9)]
    p.series(ref, "#000000", dashed=True)
    p.text(540, 60 + 18 * len(cases) + 10, "dashed black: δ^-1/2 from the cheapest case", 10)
    p.text(540, 60 + 18 * len(cases) + 26, "dashed colour: 1e6 from the origin", 10)
    p.hline(100.0, "#888", "100 µs (goal at the default δ 1e-4)")
    p.hline(1000.0, "#888", "1 ms (goal at 1e-6)")
    with open(out_path, "w") as f:
        f.write(svg_doc(W, H, p.out))


def read_csv_comments(path):
    """A CSV whose comment lines start with '#' and that may end with other text (a benchmark's stdout)."""
    with open(path, newline="") as f:
        lines = [l for l in f if l.strip() and not l.startswith("#")]
    header = lines[0].strip().split(",")
    return [r for r in csv.DictReader(lines) if len(r) == len(header) and None not in r.values()
            and r.get(header[-1]) not in (None, "")]


def main(argv):
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser = argparse.ArgumentParser(description="SVG plots of the benchmarks' results (see the module's docstring).")
    parser.add_argument("results_dir", nargs="?",
                        help="one machine's results, as the benchmarks write them "
                             "(default: samples/bench/results/vm-2core of this repository)")
    parser.add_argument("out_dir", nargs="?", help="where the SVG files go (default: docs/img of this repository)")
    args = parser.parse_args(argv[1:])
    csv_dir = args.results_dir or os.path.join(root, "samples", "bench", "results", "vm-2core")
    out_dir = args.out_dir or os.path.join(root, "docs", "img")
    os.makedirs(out_dir, exist_ok=True)
    written = []
    if os.path.exists(os.path.join(csv_dir, "bench_queries.csv")):
        path = os.path.join(out_dir, "bench_queries_pareto.svg")
        pareto_plot(csv_dir, path)
        written.append(path)
    if os.path.exists(os.path.join(csv_dir, "bench_queries_sweep.csv")):
        path = os.path.join(out_dir, "bench_queries_sweep.svg")
        sweep_plot(csv_dir, path)
        written.append(path)
    b2 = [os.path.join(csv_dir, name) for name in ("bench_box2d_scenes.csv", "bench_box2d_scenes_large.csv")]
    if os.path.exists(b2[0]):
        path = os.path.join(out_dir, "bench_box2d_scenes.svg")
        box2d_scenes_plot([p for p in b2 if os.path.exists(p)], path)
        written.append(path)
    if os.path.exists(os.path.join(csv_dir, "bench_hard_cases.csv")):
        path = os.path.join(out_dir, "bench_hard_cases.svg")
        hard_cases_plot(os.path.join(csv_dir, "bench_hard_cases.csv"), path)
        written.append(path)
    if not written:
        sys.stderr.write(f"plot_benchmarks.py: no benchmark CSV in {csv_dir}\n")
        return 1
    for w in written:
        print(w)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
