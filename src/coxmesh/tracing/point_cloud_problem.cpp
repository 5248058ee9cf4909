// The point-cloud problem: defaults from the sample spacing, frames and their diagnostics, the
// function, the tube, seeds on every component, a box.
#include "coxmesh/tracing/point_cloud_problem.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "coxmesh/lattice/simplex.h"
#include "coxmesh/util/parallel_for.h"

namespace coxmesh {

namespace {

// Up to `count` of the given samples (one component's seedable ones) spread over them:
// farthest-point sampling from the flattest (the best local plane), in a deterministic order.
std::vector<std::uint32_t> spread_samples(const SampleTree& tree, const SampleFrames& fr,
                                          const std::vector<std::uint32_t>& members, int count) {
  const int d = tree.dimension();
  std::uint32_t first = members[0];
  for (std::uint32_t i : members)
    if (fr.flatness[i] < fr.flatness[first]) first = i;
  std::vector<std::uint32_t> chosen{first};
  std::vector<double> dist(members.size(), std::numeric_limits<double>::infinity());
  while (static_cast<int>(chosen.size()) < count && chosen.size() < members.size()) {
    const double* c = tree.point(chosen.back());
    std::size_t best = 0;
    for (std::size_t j = 0; j < members.size(); ++j) {
      const double* p = tree.point(members[j]);
      double s = 0;
      for (int t = 0; t < d; ++t) s += (p[t] - c[t]) * (p[t] - c[t]);
      dist[j] = std::min(dist[j], s);
      if (dist[j] > dist[best]) best = j;
    }
    if (!(dist[best] > 0)) break;
    chosen.push_back(members[best]);
  }
  return chosen;
}

// Sample i moved onto the zero set of F along its own normals (Newton's steps with the frame as
// F's derivative, which it is near the sample), keeping the point of smallest |F| seen.
// Farthest-point sampling favours the samples that noise pushed furthest out, up to a few edge
// lengths from the traced manifold with 50,000 noisy samples: beyond the rings a seed's search
// looks through.
std::vector<double> onto_zero_set(const ImplicitFunction& f, const SampleFrames& fr, std::uint32_t i, const double* x) {
  const int d = fr.d, k = fr.k;
  const double* u = fr.frame(i);
  std::vector<double> y(x, x + d), best = y;
  std::array<double, kMaxDimension> value;
  double best_norm = std::numeric_limits<double>::infinity();
  for (int step = 0; step < 8; ++step) {
    f.evaluate(y.data(), value.data());
    double norm = 0;
    for (int j = 0; j < k; ++j) norm += value[j] * value[j];
    if (!(norm < best_norm)) break;
    best_norm = norm, best = y;
    for (int j = 0; j < k; ++j)
      for (int t = 0; t < d; ++t) y[t] -= value[j] * u[j * d + t];
  }
  return best;
}

// The radius of the largest ball tangent to the samples at sample i on the side of direction v
// (a unit normal) that holds no sample deeper than `slack` (noise and curvature of its own
// neighbourhood), at most `cap`: shrinking balls (Ma, Bae, Choi and Ng 2012), each shrunk to the
// ball tangent at the sample through the sample found inside. Another sheet at distance g along v
// gives g/2; a surface's own concave side its radius of curvature.
double empty_ball_radius(const SampleTree& tree, std::uint32_t i, const double* v, double cap, double slack) {
  const int d = tree.dimension();
  const double* p = tree.point(i);
  std::array<double, kMaxDimension> c;
  double a = cap;
  for (int step = 0; step < 16; ++step) {
    for (int t = 0; t < d; ++t) c[t] = p[t] + a * v[t];
    double d2;
    const double* q = tree.point(tree.nearest(c.data(), &d2));
    if (std::sqrt(d2) >= a - slack) return a;
    double w2 = 0, along = 0;
    for (int t = 0; t < d; ++t) w2 += (q[t] - p[t]) * (q[t] - p[t]), along += v[t] * (q[t] - p[t]);
    const double smaller = w2 / (2 * along);  // (along > 0: q is nearer to c than p is)
    if (!(smaller < a)) return a;
    a = smaller;
  }
  return a;
}

// A low quantile over every 8th sample (in the tree's order: spread over the samples) of the
// smallest empty ball along ± each normal, at most `cap`: the distance from the samples to the
// medial axis where it comes nearest (the local feature size), blind to what lies closer than `slack`.
double feature_size(const SampleTree& tree, const SampleFrames& fr, double cap, double slack, int threads) {
  const std::size_t n = tree.size(), stride = 8, probes = (n + stride - 1) / stride;
  std::vector<double> radius(probes);
  WorkerPool(std::max(threads, 1)).run(probes, [&](std::size_t j, int) {
    const std::uint32_t i = tree.sample_at(static_cast<std::uint32_t>(j * stride));
    std::array<double, kMaxDimension> v;
    double smallest = cap;
    for (int normal = 0; normal < fr.k; ++normal)
      for (double sign : {1.0, -1.0}) {
        for (int t = 0; t < fr.d; ++t) v[t] = sign * fr.frame(i)[normal * fr.d + t];
        smallest = std::min(smallest, empty_ball_radius(tree, i, v.data(), cap, slack));
      }
    radius[j] = smallest;
  });
  const std::size_t low = probes / 100;
  std::nth_element(radius.begin(), radius.begin() + low, radius.end());
  return radius[low];
}

std::string percent(double x) {
  std::ostringstream s;
  s.precision(2);
  s << std::fixed << 100 * x << " %";
  return s.str();
}

}  // namespace

PointCloudProblem make_point_cloud_problem(std::vector<double> samples, int d, int m,
                                           const PointCloudOptions& options) {
  check_dimension(d);
  if (d < 2)
    throw InputError("the samples have 1 coordinate each: meshing needs points of R^2 or more (m from 1 to d − 1)");
  if (m < 1 || m >= d)
    throw InputError("the manifold dimension m must be between 1 and d − 1 = " + std::to_string(d - 1) +
                     " for samples of R^" + std::to_string(d));
  if (samples.size() % d != 0) throw InputError("the sample array is not n × d");
  const std::size_t n = samples.size() / d;
  if (n < static_cast<std::size_t>(m) + 2)
    throw InputError(std::to_string(n) + (n == 1 ? " sample is" : " samples are") + " too few for a " +
                     std::to_string(m) + "-manifold (at least m + 2 = " + std::to_string(m + 2) + ")");
  for (double v : samples)
    if (!std::isfinite(v)) throw InputError("the samples contain NaN or infinite coordinates");
  auto positive_or_zero = [](double v, const char* what) {
    if (!(v >= 0) || !std::isfinite(v)) throw InputError(std::string(what) + " must be positive");
  };
  positive_or_zero(options.edge_length, "the edge length");
  positive_or_zero(options.radius, "the neighbourhood radius");
  positive_or_zero(options.tube, "the tube radius");
  positive_or_zero(options.blend_width, "the blending width");
  if (!(options.edge_factor >= 0) || !(options.radius_factor > 0) || !(options.blend_factor > 0))
    throw InputError("the scale factors must be positive");

  PointCloudProblem p;
  auto model = std::make_shared<SampleModel>();
  model->tree = std::make_unique<SampleTree>(std::move(samples), d);
  const SampleTree& tree = *model->tree;
  PointCloudDiagnostics& diag = p.diagnostics;
  diag.samples = n;
  diag.ambient_dimension = d;
  diag.manifold_dimension = m;
  const int threads = resolve_threads(options.threads);
  diag.spacing = median_spacing(tree, threads);
  if (!(diag.spacing > 0)) throw InputError("the samples coincide: no spacing to scale the mesh by");
  diag.radius = options.radius > 0 ? options.radius : options.radius_factor * diag.spacing;

  FrameOptions fo;
  fo.radius = diag.radius;
  fo.min_neighbours = options.min_neighbours > 0 ? options.min_neighbours : 4 * (m + 1);
  fo.max_neighbours = std::max(64, fo.min_neighbours);
  fo.reference_normals = options.normals;
  fo.threads = threads;
  diag.used_given_normals = !options.normals.empty();
  model->frames = estimate_frames(tree, m, fo);
  const SampleFrames& fr = model->frames;
  diag.mean_neighbours = fr.mean_neighbours;
  diag.components = fr.components;
  diag.graph_edges = fr.graph_edges;
  diag.compared_edges = fr.compared_edges;
  diag.frustrated_edges = fr.frustrated_edges;
  std::vector<double> thickness = fr.thickness;
  std::nth_element(thickness.begin(), thickness.begin() + n / 2, thickness.end());
  diag.thickness = thickness[n / 2];
  std::vector<std::uint8_t> spread = fr.spread_dimension;
  std::nth_element(spread.begin(), spread.begin() + n / 2, spread.end());
  diag.apparent_dimension = spread[n / 2];
  if (diag.apparent_dimension < m)
    diag.dimension_warning =
        "the samples look " + std::to_string(diag.apparent_dimension) + "-dimensional, not " + std::to_string(m) +
        "-dimensional: most of their neighbourhoods spread in only " + std::to_string(diag.apparent_dimension) +
        " direction" + (diag.apparent_dimension == 1 ? "" : "s") + " (m = " + std::to_string(diag.apparent_dimension) +
        "?); what is traced around them is a thin " + std::to_string(m) + "-manifold whose topology is not theirs";
  // A neighbourhood of radius r on a surface of curvature κ lies within RMS distance κr²/(4√3) ≈
  // κr²/7 of its plane (a uniformly sampled disc), so the median thickness t gives a radius of
  // curvature ρ ≈ r²/(7t): an overestimate where noise adds to t, infinite for flat samples.
  diag.curvature_radius = diag.radius * diag.radius / (7 * diag.thickness);
  // Curves: 2.5 spacings when the samples lie within half a spacing of their local lines, 2
  // otherwise. Surfaces alike, but up to 6 spacings where a fifth of ρ allows it (dense samples
  // of a gently curved surface): the cells per area fall with the edge's square, most in high d.
  // Measured (docs/point_clouds.md): at 2.5 a noisy open disc (noise of 1 to 1.6 spacings) got
  // holes that 2 did not, and a thin knotted tube (thickness 1 spacing) broke at 2.75; sparse or
  // noisy Klein bottles in R⁴, right at 2.5 spacings, went wrong at 3.2 where ρ/5 was 1.6 spacings.
  // Curvature is not the only limit: sheets of the samples close to each other (parallel planes, a
  // fold) are as thin a feature, seen by the thickness only within the neighbourhood radius. So the
  // longer edge must also stay within half the feature size (the nearest medial ball): two planes
  // 8 spacings apart are right at 2.5 spacings and wrong (a thousand handles) at 6.
  const bool clean = diag.thickness <= 0.5 * diag.spacing;
  double surface_factor = std::clamp(diag.curvature_radius / 5 / diag.spacing, 2.5, 6.0);
  if (m == 2 && clean && options.edge_factor <= 0 && options.edge_length <= 0 && surface_factor > 2.5) {
    diag.feature_size = feature_size(tree, fr, 2 * surface_factor * diag.spacing, 3 * diag.thickness, threads);
    surface_factor = std::clamp(diag.feature_size / 2 / diag.spacing, 2.5, surface_factor);
  }
  const double edge_factor = options.edge_factor > 0 ? options.edge_factor
                             : m == 1                ? (clean ? 2.5 : 2.0)
                             : m == 2                ? (clean ? surface_factor : 2.0)
                                                     : 2.0 * (m - 1);
  // Noisy samples: scaled by the thickness beyond a spacing, so that the lattice does not resolve
  // the noise (with the wider blend below: 50,000 samples of a sphere or a torus with noise of 1.8
  // spacings, thickness 1.4, had handles with edges of 2 spacings and a blend of 2 thicknesses, in
  // 3 runs of 3 for the sphere, and none with 2 and 2.7 thicknesses).
  diag.edge_length = options.edge_length > 0 ? options.edge_length
                     : clean || m > 2        ? edge_factor * diag.spacing
                                             : edge_factor * std::max(diag.spacing, diag.thickness);
  // Orientable manifolds give no frustrated edges but a few isolated ones at sharp features or in
  // noise; a non-orientable one gives a seam of them across the manifold, whose edge count grows
  // like n^((m-1)/m), at least √n for m ≥ 2 (RP² ⊂ R⁴: 5-6 √E from 2,000 to 50,000 samples).
  diag.frames_inconsistent = fr.frustrated_edges > std::max(8.0, std::sqrt(static_cast<double>(fr.compared_edges)));
  if (diag.frames_inconsistent) {
    std::ostringstream w;
    w << fr.frustrated_edges << " of " << fr.compared_edges << " neighbour-graph edges ("
      << percent(static_cast<double>(fr.frustrated_edges) / std::max<std::size_t>(fr.compared_edges, 1))
      << ") join samples whose normal " << (fr.k == 1 ? "directions" : "frames")
      << " cannot be made consistent: the manifold looks non-orientable (like RP^2 or the Klein bottle in R^4, "
         "which no function R^d -> R^k can represent), or the samples are too sparse or noisy for their normals; "
         "the traced topology cannot be trusted";
    diag.warning = w.str();
  }

  p.model = model;
  p.edge_length = diag.edge_length;
  // Where the samples scatter further from their planes than they are apart, the blend averages
  // over that scatter, and faster beyond (1.5 times from a thickness of 1.5 spacings on; the edge
  // length above says where it was measured).
  const double noisiness = std::clamp(diag.thickness / diag.spacing, 1.0, 1.5);
  diag.blend_width = options.blend_width > 0
                         ? options.blend_width
                         : options.blend_factor * std::max(diag.spacing, diag.thickness) * noisiness;
  p.function = options.function == PointCloudFunction::nearest ? nearest_frame_function(model)
                                                               : blended_frame_function(model, diag.blend_width);
  if (options.function == PointCloudFunction::nearest) diag.blend_width = 0;
  // The tube reaches at least 3/4 of the largest gap in the samples: M crosses a gap at half its
  // length from the samples (random samples of a curve have gaps of ln(n) mean spacings).
  diag.longest_gap = fr.longest_gap;
  diag.tube_radius = options.tube > 0 ? std::max(options.tube * diag.edge_length, 0.75 * fr.longest_gap) : 0;
  if (options.tube > 0) p.domain = tube_domain(model, diag.tube_radius);

  // Seeds: samples spread over every component of the neighbour graph, among those with at least
  // m + 1 others within the radius (a plane's worth). Isolated samples (outliers) are joined to the
  // graph by the minimum count, and farthest-point sampling would pick them first: the little
  // sheets through them would be traced as extra components.
  std::vector<std::vector<std::uint32_t>> members(fr.components);
  for (std::size_t i = 0; i < n; ++i) {
    if (fr.within_radius[i] >= m + 1)
      members[fr.component[i]].push_back(static_cast<std::uint32_t>(i));
    else
      ++diag.isolated_samples;
  }
  for (const auto& component : members) {
    if (component.empty()) {
      ++diag.unseeded_components;
      continue;
    }
    for (std::uint32_t i : spread_samples(tree, fr, component, std::max(1, options.seeds_per_component)))
      p.seeds.push_back(onto_zero_set(*p.function, fr, i, tree.point(i)));
  }
  if (p.seeds.empty())
    throw InputError("no sample has " + std::to_string(m + 1) + " others within the neighbourhood radius " +
                     std::to_string(diag.radius) + ": the samples are too sparse for it (give a larger radius)");

  // A box around the samples: the tube bounds the walk already; this also bounds it without one.
  const double margin = (options.tube > 0 ? diag.tube_radius : 10 * diag.radius) + 2 * diag.edge_length;
  p.box.lo.assign(d, std::numeric_limits<double>::infinity());
  p.box.hi.assign(d, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < n; ++i)
    for (int t = 0; t < d; ++t) {
      p.box.lo[t] = std::min(p.box.lo[t], tree.point(i)[t] - margin);
      p.box.hi[t] = std::max(p.box.hi[t], tree.point(i)[t] + margin);
    }
  return p;
}

}  // namespace coxmesh
