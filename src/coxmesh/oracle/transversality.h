// Thesis §4.3: the exact transversality rule (Allgower–Georg "completely labelled" simplices).
#pragma once

namespace coxmesh {

class SmallLu;

/// The lexicographic (symbolic perturbation) test of a k-simplex against F̂ = 0, n = k + 1.
/// `m` is the n × n matrix, column-major, column j = (1, F(v_j)). τ is transverse iff M is
/// non-singular and every row of M^{-1} is lexicographically positive (its first non-zero entry
/// is > 0): τ then meets F̂^{-1}(ε, ε², …, ε^k) for all small ε > 0, a regular level, so every
/// (k+1)-simplex has exactly 0 or 2 transverse facets even when vertices lie on M.
/// On success `lambda` (n values, ≥ 0, summing to 1) = the first column of M^{-1}: the barycentric
/// coordinates of the unperturbed intersection point.
/// Signs are decided in double precision when a forward error bound certifies them, else in
/// double-word (about 106-bit) arithmetic with its own bound (tiny entries: values of F that are
/// rounding noise); only what neither certifies (exact zeros, ill-conditioned M) is recomputed in
/// exact rational arithmetic. A vertex exactly on M reduces the question to a k × k one.
/// When `lu` is given and the answer is true, `*factored` tells whether `*lu` holds M's factors
/// (as SmallLu::factor(n, m) leaves them) with `lambda` = lu->solve_unit(0): the common case, which
/// the door-in/door-out walk then need not factor again.
bool lexicographic_solve(int n, const double* m, double* lambda, SmallLu* lu = nullptr, bool* factored = nullptr);

}  // namespace coxmesh
