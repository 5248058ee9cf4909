// Triangulation core, side by side with GUDHI's Coxeter_triangulation module (thesis Ch. 3, §4.4):
//   * point location in Ã_d (general matrix: GUDHI's own matrix passed to coxmesh, so both locate in
//     the same triangulation), on the same pre-generated random points;
//   * cofacet enumeration (cofaces of dimension k+1) of the same random k-simplices.
// Benchmark names are "<case>/coxmesh" and "<case>/gudhi"; bench/run_triangulation.sh pairs them.
#include <benchmark/benchmark.h>

// GUDHI's headers are included as system headers (see bench/CMakeLists.txt).
#include <gudhi/Coxeter_triangulation.h>
#include <gudhi/Permutahedral_representation.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "../tests/gudhi/gudhi_interop.h"
#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/simplex.h"
#include "coxmesh/triangulation/triangulation.h"

namespace {

namespace gct = Gudhi::coxeter_triangulation;
using GSimplex = gct::Permutahedral_representation<std::vector<int>, std::vector<std::vector<std::size_t>>>;
using coxmesh::Simplex;
using gudhi_interop::random_simplex;
using gudhi_interop::to_gudhi;

constexpr std::uint64_t kSeed = 20240601;
constexpr int kPoints = 1024;   // point pool, cycled through
constexpr int kSimplices = 64;  // simplex pool; one benchmark iteration enumerates all of them

void add_size_counters(benchmark::State& state, int d) {
  state.counters["simplex_bytes"] = sizeof(Simplex);
  state.counters["packed_key_bytes"] = coxmesh::packed_words(d) * 4;
}

// ---- Point location in Ã_d -------------------------------------------------------------------------

struct LocateCase {
  int d;
  gct::Coxeter_triangulation<GSimplex> gudhi;
  coxmesh::Triangulation ours;
  std::vector<std::vector<double>> points;

  explicit LocateCase(int dim) : d(dim), gudhi(dim), ours(gudhi.matrix(), gudhi.offset()) {
    std::mt19937_64 rng(kSeed + dim);
    std::uniform_real_distribution<double> u(-10.0, 10.0);
    points.assign(kPoints, std::vector<double>(dim));
    for (auto& p : points)
      for (double& v : p) v = u(rng);
  }
};

void locate_coxmesh(benchmark::State& state, const LocateCase* c) {
  std::size_t i = 0;
  for (auto _ : state) {
    const Simplex s = c->ours.locate(c->points[i].data());
    benchmark::DoNotOptimize(s);
    i = (i + 1) % kPoints;
  }
  state.SetItemsProcessed(state.iterations());
  add_size_counters(state, c->d);
}

void locate_gudhi(benchmark::State& state, const LocateCase* c) {
  std::size_t i = 0;
  for (auto _ : state) {
    const GSimplex s = c->gudhi.locate_point(c->points[i]);
    benchmark::DoNotOptimize(s.vertex().data());
    benchmark::DoNotOptimize(s.partition().data());
    i = (i + 1) % kPoints;
  }
  state.SetItemsProcessed(state.iterations());
}

// ---- Cofacet enumeration -------------------------------------------------------------------------

struct CofacetCase {
  int d, k;
  std::vector<Simplex> ours;
  std::vector<GSimplex> gudhi;
  std::uint64_t cofacets = 0;  // per pass over the pool

  CofacetCase(int dim, int kk) : d(dim), k(kk) {
    std::mt19937_64 rng(kSeed * 31 + dim * 100 + kk);
    for (int t = 0; t < kSimplices; ++t) {
      ours.push_back(random_simplex(rng, dim, kk, 100));
      gudhi.push_back(to_gudhi(ours.back()));
      cofacets += coxmesh::coface_count(ours.back(), kk + 1);
    }
  }
};

void cofacets_coxmesh(benchmark::State& state, const CofacetCase* c) {
  std::int64_t n = 0;
  for (auto _ : state) {
    std::int64_t sum = 0;
    for (const Simplex& s : c->ours) {
      coxmesh::CofaceEnumerator e(s, c->k + 1);
      while (const Simplex* mu = e.next()) {  // like GUDHI's iterator: a view, no copy
        sum += mu->y[0];
        ++n;
      }
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(n);
  state.counters["cofacets_per_pass"] = static_cast<double>(c->cofacets);
  add_size_counters(state, c->d);
}

void cofacets_gudhi(benchmark::State& state, const CofacetCase* c) {
  std::int64_t n = 0;
  for (auto _ : state) {
    std::int64_t sum = 0;
    for (const GSimplex& s : c->gudhi)
      for (const auto& mu : s.coface_range(c->k + 1)) {
        sum += mu.vertex()[0];
        ++n;
      }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(n);
  state.counters["cofacets_per_pass"] = static_cast<double>(c->cofacets);
}

}  // namespace

int main(int argc, char** argv) {
  std::printf("sizeof(coxmesh::Simplex) = %zu bytes (fixed, no heap)\n", sizeof(Simplex));
  std::printf("packed key (coxmesh::pack, d + ceil((d+1)/4) words):");
  for (int d : {3, 5, 10, 20}) std::printf("  d=%d: %d B", d, coxmesh::packed_words(d) * 4);
  std::printf(
      "\nGUDHI simplex: sizeof = %zu bytes + heap: vertex vector (4d B) + partition vector "
      "(24 B per part) + parts (8 B per index), k+3 allocations\n",
      sizeof(GSimplex));

  std::vector<std::unique_ptr<LocateCase>> locate_cases;
  std::vector<std::unique_ptr<CofacetCase>> cofacet_cases;
  for (int d : {3, 5, 10, 20}) {
    locate_cases.push_back(std::make_unique<LocateCase>(d));
    const LocateCase* c = locate_cases.back().get();
    const std::string name = "locate/coxeter/d=" + std::to_string(d);
    benchmark::RegisterBenchmark((name + "/coxmesh").c_str(), locate_coxmesh, c);
    benchmark::RegisterBenchmark((name + "/gudhi").c_str(), locate_gudhi, c);
  }
  for (int d : {3, 5, 10, 20}) {
    std::vector<int> ks;
    if (d <= 5) ks.push_back(0);
    for (int k : {d / 2, d - 3, d - 2, d - 1})
      if (k >= 0 && std::find(ks.begin(), ks.end(), k) == ks.end()) ks.push_back(k);
    std::sort(ks.begin(), ks.end());
    for (int k : ks) {
      cofacet_cases.push_back(std::make_unique<CofacetCase>(d, k));
      const CofacetCase* c = cofacet_cases.back().get();
      const std::string name = "cofacets/d=" + std::to_string(d) + "/k=" + std::to_string(k);
      benchmark::RegisterBenchmark((name + "/coxmesh").c_str(), cofacets_coxmesh, c);
      benchmark::RegisterBenchmark((name + "/gudhi").c_str(), cofacets_gudhi, c);
    }
  }

  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
