#!/usr/bin/env python3
"""Regenerates docs/point_cloud_correctness.svg: how often `coxmesh trace --points` (default oracle:
one function value per lattice vertex) gives the right Z/2 Betti numbers of S^2 and of a torus in
R^3, against the number of samples (clean) and against Gaussian noise in units of the sample spacing
(2,000 samples). Every point is the fraction of right runs over a few generator seeds.

    usage: docs/gen_point_cloud_plot.py          (uses $COXMESH, else build/src/coxmesh)
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.environ.get("COXMESH", os.path.join(ROOT, "build", "src", "coxmesh"))
OUT = os.path.join(ROOT, "docs", "point_cloud_correctness.svg")

DENSITIES = [60, 125, 250, 500, 1000, 2000, 4000, 10000]
NOISES = [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0]  # sigma / spacing
NOISE_SAMPLES = 2000
SEEDS = [1, 2, 3, 4, 5]
SHAPES = {"sphere": [1, 0, 1], "torus": [1, 2, 1]}


def sample(shape, n, rng):
    """n area-uniform samples of the unit sphere or of the torus of radii 1 and 0.4."""
    if shape == "sphere":
        x = rng.normal(size=(n, 3))
        return x / np.linalg.norm(x, axis=1, keepdims=True)
    out = []
    while len(out) < n:  # area element proportional to 1 + 0.4 cos b: rejection
        a, b, u = rng.uniform(0, 2 * np.pi), rng.uniform(0, 2 * np.pi), rng.uniform(0, 1.4)
        if u <= 1 + 0.4 * np.cos(b):
            r = 1 + 0.4 * np.cos(b)
            out.append((r * np.cos(a), r * np.sin(a), 0.4 * np.sin(b)))
    return np.array(out)


def spacing(x):
    """Median nearest-neighbour distance (what coxmesh scales everything by)."""
    best = np.full(len(x), np.inf)
    for i in range(0, len(x), 500):
        d2 = ((x[i:i + 500, None, :] - x[None, :, :]) ** 2).sum(-1)
        d2[np.arange(d2.shape[0]), np.arange(i, i + d2.shape[0])] = np.inf
        best[i:i + 500] = d2.min(1)
    return float(np.sqrt(np.median(best)))


def right(x, expected, tmp):
    path = os.path.join(tmp, "samples.xyz")
    np.savetxt(path, x)
    run = subprocess.run([BIN, "trace", "--points", path, "--m", "2", "--json", "--no-output", "--threads", "2"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        return False
    j = json.loads(run.stdout)
    return j.get("complete", False) and j.get("betti") == expected


def fraction(shape, n, noise, tmp):
    ok = 0
    for seed in SEEDS:
        rng = np.random.default_rng(1000 * seed + n)
        x = sample(shape, n, rng)
        if noise > 0:
            x = x + rng.normal(scale=noise * spacing(x), size=x.shape)
        ok += right(x, SHAPES[shape], tmp)
    return ok / len(SEEDS)


def panel(x0, y0, w, h, xs, series, xlabel, log):
    """One panel: fraction right (0..1) against xs, one polyline per shape."""
    def px(v):
        t = (np.log(v) - np.log(xs[0])) / (np.log(xs[-1]) - np.log(xs[0])) if log else (v - xs[0]) / (xs[-1] - xs[0])
        return x0 + t * w

    def py(f):
        return y0 + h - f * h

    s = [f'<rect x="{x0}" y="{y0}" width="{w}" height="{h}" fill="none" stroke="black"/>']
    for f in (0, 0.5, 1):
        s.append(f'<line x1="{x0}" y1="{py(f):.1f}" x2="{x0 + w}" y2="{py(f):.1f}" stroke="#ddd"/>')
        s.append(f'<text x="{x0 - 6}" y="{py(f) + 4:.1f}" text-anchor="end">{f:g}</text>')
    for v in xs:
        s.append(f'<text x="{px(v):.1f}" y="{y0 + h + 16}" text-anchor="middle">{v:g}</text>')
    s.append(f'<text x="{x0 + w / 2}" y="{y0 + h + 36}" text-anchor="middle">{xlabel}</text>')
    s.append(f'<text x="{x0 - 40}" y="{y0 + h / 2}" text-anchor="middle" '
             f'transform="rotate(-90 {x0 - 40} {y0 + h / 2})">fraction with right Betti numbers</text>')
    for (name, ys), colour, dy in zip(series.items(), ("#1f77b4", "#d62728"), (-2, 2)):
        pts = " ".join(f"{px(v):.1f},{py(f) + dy:.1f}" for v, f in zip(xs, ys))
        s.append(f'<polyline points="{pts}" fill="none" stroke="{colour}" stroke-width="2"/>')
        s += [f'<circle cx="{px(v):.1f}" cy="{py(f) + dy:.1f}" r="3" fill="{colour}"/>' for v, f in zip(xs, ys)]
    return s


def main():
    if not os.access(BIN, os.X_OK):
        sys.exit(f"gen_point_cloud_plot.py: no coxmesh binary at {BIN} (build it or set COXMESH)")
    by_n, by_noise = {}, {}
    with tempfile.TemporaryDirectory() as tmp:
        for shape in SHAPES:
            by_n[shape] = [fraction(shape, n, 0.0, tmp) for n in DENSITIES]
            by_noise[shape] = [fraction(shape, NOISE_SAMPLES, s, tmp) for s in NOISES]
            print(shape, "by n:", by_n[shape], "by noise:", by_noise[shape])
    svg = ['<?xml version="1.0" encoding="UTF-8"?>',
           '<svg xmlns="http://www.w3.org/2000/svg" width="820" height="340" viewBox="0 0 820 340" '
           'font-family="sans-serif" font-size="12">',
           '<rect width="100%" height="100%" fill="white"/>',
           '<text x="410" y="22" text-anchor="middle" font-size="15">coxmesh trace --points: right Z/2 Betti '
           f'numbers ({len(SEEDS)} seeds per point, default oracle)</text>']
    svg += panel(80, 50, 300, 220, DENSITIES, by_n, "samples n (clean; log scale)", True)
    svg += panel(490, 50, 300, 220, NOISES, by_noise, f"noise sigma / spacing (n = {NOISE_SAMPLES})", False)
    for i, (name, colour) in enumerate(zip(SHAPES, ("#1f77b4", "#d62728"))):
        svg.append(f'<line x1="{330 + 130 * i}" y1="325" x2="{355 + 130 * i}" y2="325" stroke="{colour}" '
                   'stroke-width="2"/>')
        svg.append(f'<text x="{360 + 130 * i}" y="329">{"S^2" if name == "sphere" else "torus"} in R^3</text>')
    svg.append("</svg>")
    with open(OUT, "w") as f:
        f.write("\n".join(svg) + "\n")


if __name__ == "__main__":
    main()
