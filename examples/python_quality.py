"""The quality table of the Coxeter triangulations (thesis Ch. 2) as Python data.

    PYTHONPATH=build/python python3 examples/python_quality.py
"""
import coxmesh

rows = coxmesh.quality(max_dim=6)
print(f"{'type':>4} {'d':>2} {'thickness':>10} {'r/R':>8} {'Delaunay':>10} {'protection':>10}")
for r in rows:
    protection = "-" if r["protection"] is None else f"{r['protection']:.4f}"
    print(f"{r['type']:>4} {r['dimension']:>2} {r['thickness']:>10.4f} {r['radius_ratio']:>8.4f} {r['delaunay']:>10} {protection:>10}")
best = max((r for r in rows if r["dimension"] == 4), key=lambda r: r["thickness"])
print("thickest in d = 4:", best["type"])
