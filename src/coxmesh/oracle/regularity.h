// Is 0 a regular value of F where the manifold was traced? The tracer's exact rule always yields
// a PL manifold: where F's differential degenerates on F = 0 (F = G², F ≥ 0, dependent equations,
// a domain tangent to M) it meshes a perturbed level set near it, which is correct but surprising.
// These measures let a front end say so.
#pragma once

#include <span>
#include <vector>

#include "coxmesh/oracle/implicit_function.h"

namespace coxmesh {

/// How regular the map x ↦ (f_1(x), f_2(x), …) (the functions' equations stacked, all on R^d) is at
/// x, at scale h: the smallest singular value of its Jacobian at x (k ≤ d rows, central differences
/// of step h/8) after each row is divided by the largest norm that row's gradient reaches at x and
/// at the 2d points x ± 4h·e_i. About 1 where the differential has full rank and varies slowly; near 0
/// where an equation's gradient vanishes at x but not around it (F = G² on G = 0, x² + y² + z² at
/// the origin), where the equations are dependent, or where F vanishes identically (no gradient
/// anywhere: 0). NaN where a function is not finite near x. Costs (2d + 1)·2d evaluations.
double regularity(std::span<const ImplicitFunction* const> functions, const double* x, double h);

/// singular_on's defaults: the points tested, and the measure below which a point counts as singular.
inline constexpr int kRegularitySamples = 48;
inline constexpr double kRegularityThreshold = 0.02;

/// A conservative verdict on points of a traced set (rows of d coordinates, a sample of which is
/// tested, at most `samples`, evenly spaced): true when more than a quarter of the finite measures
/// are below `threshold`.
bool singular_on(std::span<const ImplicitFunction* const> functions, std::span<const double> points, double h,
                 int samples = kRegularitySamples, double threshold = kRegularityThreshold);

}  // namespace coxmesh
