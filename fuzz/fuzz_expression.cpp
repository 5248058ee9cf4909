// Functions and domains typed as text (muparser front end). Input: one byte choosing the
// dimension and the kind, then the text. An accepted function is evaluated at a few points.
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "coxmesh/oracle/expression_function.h"
#include "coxmesh/oracle/intersection_oracle.h"

using namespace coxmesh;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const int selector = data[0];
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  // Low 5 bits: the dimension (0: inferred from the variables); bit 5: a domain instead.
  const int dim = selector & 31;
  const bool domain = (selector & 32) != 0;
  FunctionPtr f;
  try {
    if (domain)
      f = expression_domain(text, dim == 0 ? 3 : dim);
    else
      f = dim == 0 ? expression_function(text) : expression_function(text, dim);
  } catch (const InputError&) {
    return 0;
  }
  const int d = f->ambient_dimension(), k = f->codimension();
  if (d < 1 || d > kMaxDimension || k < 1 || k >= d + (domain ? 1 : 0)) std::abort();
  std::vector<double> x(d), value(k);
  for (double v : {0.0, 0.5, -1.25, 3.0, 1e300, -1e-300}) {
    for (int i = 0; i < d; ++i) x[i] = v * (i % 2 ? -1 : 1) + 0.125 * i;
    try {
      f->evaluate(x.data(), value.data());
    } catch (const EvaluationError&) {
    } catch (const InputError&) {
    }
  }
  return 0;
}
