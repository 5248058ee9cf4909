#!/usr/bin/env python3
"""The point-cloud table of docs/benchmarks.md ("Point clouds"): `coxmesh trace --points FILE --m M
--threads 1 --json --no-output` with default parameters on random samples (NumPy, seed 7) of the
unit sphere, the torus of radii 1 and 0.4 (uniform by area), S^1 x S^1 in R^4 and the unit S^3 in
R^4, with Gaussian noise sigma on every coordinate. Per sample: the process's CPU time (user +
system; one thread, so what a quiet machine's wall time would be), best of RUNS; peak resident
memory by /usr/bin/time (Debian package time).

    usage: bench/bench_point_cloud_cli.py [COXMESH_BINARY] [RUNS]   (default build/src/coxmesh, 3)
"""
import json
import os
import resource
import subprocess
import sys
import tempfile

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "src", "coxmesh")
RUNS = int(sys.argv[2]) if len(sys.argv) > 2 else 3
CASES = [("S²", 2000, 0), ("S²", 2000, 0.01), ("S²", 10000, 0), ("S²", 10000, 0.01), ("S²", 50000, 0),
         ("S²", 50000, 0.01), ("torus", 2000, 0), ("torus", 2000, 0.01), ("torus", 10000, 0),
         ("torus", 10000, 0.01), ("torus", 50000, 0), ("torus", 50000, 0.01), ("flat torus", 10000, 0),
         ("flat torus", 10000, 0.01), ("S³", 50000, 0), ("S³", 50000, 0.01)]


def sample(shape, n, rng):
    if shape in ("S²", "S³"):
        x = rng.normal(size=(n, 3 if shape == "S²" else 4))
        return x / np.linalg.norm(x, axis=1, keepdims=True)
    if shape == "flat torus":
        a, b = rng.uniform(0, 2 * np.pi, n), rng.uniform(0, 2 * np.pi, n)
        return np.stack([np.cos(a), np.sin(a), np.cos(b), np.sin(b)], 1)
    out = np.empty((0, 3))
    while len(out) < n:  # the area element is proportional to 1 + 0.4 cos b: rejection
        a, b, u = rng.uniform(0, 2 * np.pi, n), rng.uniform(0, 2 * np.pi, n), rng.uniform(0, 1.4, n)
        keep = u <= 1 + 0.4 * np.cos(b)
        r = 1 + 0.4 * np.cos(b[keep])
        out = np.vstack([out, np.stack([r * np.cos(a[keep]), r * np.sin(a[keep]), 0.4 * np.sin(b[keep])], 1)])
    return out[:n]


def run(path, m, tmp):
    # Peak memory by /usr/bin/time: a child forked from Python reports Python's size as its own.
    peak = os.path.join(tmp, "peak")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", peak, BIN, "trace", "--points", path, "--m", str(m),
                        "--threads", "1", "--json", "--no-output"], capture_output=True, text=True, check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    with open(peak) as f:
        kib = int(f.read().split()[-1])
    return json.loads(p.stdout), (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), kib


def main():
    print("| samples | n | σ | spacing | edge (spacings) | \\|S\\| | Betti (Z/2) | manifold | prepare s | trace s | "
          "complex s | topology s | CPU s | µs/sample | peak MiB |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for shape, n, sigma in CASES:
            rng = np.random.default_rng(7)
            x = sample(shape, n, rng)
            x = x + sigma * rng.normal(size=x.shape)
            path = os.path.join(tmp, "samples.npy")
            np.save(path, x)
            best = None
            for _ in range(RUNS):
                j, cpu, kib = run(path, 3 if shape == "S³" else 2, tmp)
                if best is None or cpu < best[1]:
                    best = (j, cpu, kib)
            j, cpu, kib = best
            pc, t = j["point_cloud"], j["timings"]
            print(f"| {shape} | {n:,} | {sigma} | {pc['spacing']:.4f} | {pc['edge_length']:.4f} "
                  f"({pc['edge_length'] / pc['spacing']:.1f}) | {j['traced_simplices']:,} | "
                  f"{' '.join(map(str, j['betti']))} | {'yes' if j['is_manifold'] else 'no'} | "
                  f"{pc['setup_seconds']:.2f} | {t['trace_seconds']:.2f} | {t['cell_complex_seconds']:.2f} | {t['topology_seconds']:.2f} | "
                  f"{cpu:.2f} | **{1e6 * cpu / n:.0f}** | {kib // 1024} |", flush=True)


main()
