// The reference for the Python package's bulk Triangulation.locate: the same work as a plain C++
// loop (locate, then barycentric coordinates, into arrays allocated beforehand) on n uniform random
// points of [-1, 1]^d in Ã_d with longest edge 0.1. One thread, median of `runs`.
// Usage: bench_locate_loop [n=1000000] [d=3] [runs=5]. Prints the median seconds.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "coxmesh/triangulation/triangulation.h"

int main(int argc, char** argv) {
  const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1'000'000;
  const int d = argc > 2 ? std::atoi(argv[2]) : 3;
  const int runs = argc > 3 ? std::atoi(argv[3]) : 5;
  const coxmesh::Triangulation t = coxmesh::Triangulation::coxeter(d).with_longest_edge(0.1);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x(n * d), lambda(n * (d + 1));
  std::vector<std::int32_t> vertex(n * d);
  std::vector<std::uint8_t> blocks(n * (d + 1));
  for (double& v : x) v = u(rng);
  std::vector<double> seconds;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < n; ++i) {
      const double* p = x.data() + i * d;
      const coxmesh::Simplex s = t.locate(p);
      std::memcpy(vertex.data() + i * d, s.y.data(), sizeof(std::int32_t) * d);
      std::memcpy(blocks.data() + i * (d + 1), s.block.data(), d + 1);
      t.barycentric(s, p, lambda.data() + i * (d + 1));
      std::fill(lambda.data() + i * (d + 1) + s.k + 1, lambda.data() + (i + 1) * (d + 1), 0.0);
    }
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(seconds.begin(), seconds.end());
  std::printf("%.6f\n", seconds[seconds.size() / 2]);
}
