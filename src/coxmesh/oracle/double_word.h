// Double-word ("double-double") arithmetic: a value is an unevaluated sum hi + lo of two doubles,
// about 106 bits of precision. The exact transversality rule uses it as a second filter between
// plain double precision and exact rationals (transversality.cpp). The algorithms are the
// accurate ones of Joldes, Muller and Popescu, "Tight and rigorous error bounds for basic building
// blocks of double-word arithmetic" (ACM TOMS 44, 2017): each operation has a relative error below
// kDoubleWordUnit, so the usual error analysis of Gaussian elimination holds with that unit
// roundoff (as long as nothing overflows or underflows).
#pragma once

#include <cmath>
#include <limits>

namespace coxmesh {

struct DoubleWord {
  double hi = 0, lo = 0;
};

/// A bound of the relative error of every operation below (at most 5u² for u = 2⁻⁵³; this is
/// 32u²).
inline constexpr double kDoubleWordUnit =
    32.0 * (std::numeric_limits<double>::epsilon() / 2) * (std::numeric_limits<double>::epsilon() / 2);

namespace double_word_detail {
inline DoubleWord two_sum(double a, double b) {
  const double s = a + b, bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}
inline DoubleWord fast_two_sum(double a, double b) {  // |a| ≥ |b| (or a = 0)
  const double s = a + b;
  return {s, b - (s - a)};
}
inline DoubleWord two_prod(double a, double b) {
  const double p = a * b;
  return {p, std::fma(a, b, -p)};
}
}  // namespace double_word_detail

inline DoubleWord operator+(DoubleWord x, DoubleWord y) {  // AccurateDWPlusDW, error ≤ 3u² + 13u³
  using namespace double_word_detail;
  const DoubleWord s = two_sum(x.hi, y.hi), t = two_sum(x.lo, y.lo);
  const DoubleWord v = fast_two_sum(s.hi, s.lo + t.hi);
  return fast_two_sum(v.hi, t.lo + v.lo);
}
inline DoubleWord operator-(DoubleWord x) { return {-x.hi, -x.lo}; }
inline DoubleWord operator-(DoubleWord x, DoubleWord y) { return x + -y; }
inline DoubleWord operator*(DoubleWord x, DoubleWord y) {  // DWTimesDW3 (with fma), error ≤ 4u²
  using namespace double_word_detail;
  const DoubleWord c = two_prod(x.hi, y.hi);
  const double t0 = x.lo * y.lo, t1 = std::fma(x.hi, y.lo, t0), c2 = std::fma(x.lo, y.hi, t1);
  return fast_two_sum(c.hi, c.lo + c2);
}
// The quotient of the high words, corrected by the remainder x − y·q computed in double words:
// an error of about 5u² (the correction, itself about u·|x/y|, is computed to about 3u).
inline DoubleWord operator/(DoubleWord x, DoubleWord y) {
  using namespace double_word_detail;
  const double th = x.hi / y.hi;
  const DoubleWord p = two_prod(y.hi, th);  // DWTimesFP(y, th)
  const DoubleWord r = fast_two_sum(p.hi, std::fma(y.lo, th, p.lo));
  const DoubleWord d = x - r;
  return fast_two_sum(th, d.hi / y.hi);
}

}  // namespace coxmesh
