// Locates a point in the Coxeter triangulation Ã_2 and prints its simplex, vertices and
// barycentric coordinates (a worked example computed with GUDHI), then its faces and cofaces.
#include <iostream>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"
#include "coxmesh/triangulation/triangulation.h"

int main() {
  using namespace coxmesh;
  const Triangulation t = Triangulation::coxeter(2);  // unit heights, equilateral triangles
  const double x[2] = {0.3, 0.7};
  const Simplex s = t.locate(x);
  std::cout << "point (0.3, 0.7) lies in " << s << " (dimension " << s.dimension() << ")\n";
  double xs[3 * 2], lambda[3];
  t.vertex_coordinates(s, xs);
  t.barycentric(s, x, lambda);
  for (int j = 0; j <= s.dimension(); ++j)
    std::cout << "  vertex " << j << " = (" << xs[2 * j] << ", " << xs[2 * j + 1] << "), weight " << lambda[j] << "\n";
  std::cout << "edges of it:\n";
  FaceEnumerator edges(s, 1);
  for (Simplex e; edges.next(e);) std::cout << "  " << e << "\n";
  std::cout << "triangles around its first vertex:\n";
  FaceEnumerator vertices(s, 0);
  Simplex v;
  vertices.next(v);
  CofaceEnumerator star(v, 2);
  for (Simplex c; star.next(c);) std::cout << "  " << c << "\n";
}
