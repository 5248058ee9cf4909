"""Speed of the Python package against the C++ it wraps (not a test: prints a Markdown table).

  * tracing S^2 in R^3 from a numpy-vectorised callable against the built-in preset (one thread,
    the same triangulation and seed; trace phase only, and the whole trace() call);
  * Triangulation.locate of 10^6 points against the same work as a plain C++ loop
    (bench_locate_loop, built with the benchmarks);
  * the time of `import coxmesh` in a fresh interpreter (numpy included) and of numpy alone.

Usage, from the repository root after a build with the benchmarks:
    PYTHONPATH=build/python python3 bench/bench_python.py [--build build] [--runs 5]
"""
import argparse
import statistics
import subprocess
import sys
import time

import numpy as np

import coxmesh


def median_of(runs, fn):
    return statistics.median(fn() for _ in range(runs))


def sphere(X):
    return X[:, 0] ** 2 + X[:, 1] ** 2 + X[:, 2] ** 2 - 1


def tracing(runs, edge):
    # Preset and callable runs alternate, so that load from elsewhere on the machine hits both alike.
    def once(**kw):
        start = time.perf_counter()
        mesh = coxmesh.trace(edge_length=edge, seeds=[[1, 0, 0]], threads=1, **kw)
        return mesh.timings["trace_seconds"], time.perf_counter() - start, mesh

    preset, python = [], []
    for _ in range(runs):
        preset.append(once(preset="sphere"))
        python.append(once(function=sphere, dim=3))
    mesh = preset[0][2]
    assert python[0][2].cells == mesh.cells
    med = lambda results, i: statistics.median(r[i] for r in results)
    return [("trace S^2 in R^3, %d simplices: trace phase" % mesh.traced_simplices, med(preset, 0), med(python, 0)),
            ("trace S^2 in R^3: whole trace() call", med(preset, 1), med(python, 1))], mesh.function_evaluations


def locate(runs, build, n=1_000_000):
    T = coxmesh.Triangulation.coxeter(3).with_longest_edge(0.1)
    X = np.random.default_rng(1).uniform(-1, 1, size=(n, 3))

    def once():
        start = time.perf_counter()
        T.locate(X)
        return time.perf_counter() - start

    python = median_of(runs, once)
    loop = float(subprocess.run([f"{build}/bench/bench_locate_loop", str(n), "3", str(runs)], check=True,
                                capture_output=True, text=True).stdout)
    return [("locate 10^6 points in Ã_3 (with barycentric coordinates)", loop, python)]


def import_time(runs):
    def fresh(code):
        out = subprocess.run([sys.executable, "-c", "import time; t = time.perf_counter(); " + code +
                              "; print(time.perf_counter() - t)"], check=True, capture_output=True, text=True)
        return float(out.stdout)

    return median_of(runs, lambda: fresh("import coxmesh")), median_of(runs, lambda: fresh("import numpy"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--edge", type=float, default=0.0125, help="longest edge of the ambient triangulation")
    args = parser.parse_args()
    rows, evaluations = tracing(args.runs, args.edge)
    rows += locate(args.runs, args.build)
    print("| what | C++ (s) | Python (s) | ratio |")
    print("|---|--:|--:|--:|")
    for what, cpp, py in rows:
        print(f"| {what} | {cpp:.3f} | {py:.3f} | {py / cpp:.2f} |")
    coxmesh_s, numpy_s = import_time(args.runs)
    print(f"\n`import coxmesh`: {coxmesh_s * 1000:.0f} ms in a fresh interpreter ({numpy_s * 1000:.0f} ms of it numpy's); "
          f"the callable was called for {evaluations} lattice vertices. Median of {args.runs} runs.")


if __name__ == "__main__":
    main()
