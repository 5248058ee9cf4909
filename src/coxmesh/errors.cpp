#include "coxmesh/errors.h"

#include <cstdio>
#include <cstdlib>

namespace coxmesh {

void assertion_failed(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "coxmesh: internal error: assertion %s failed at %s:%d\n", condition, file, line);
  std::abort();
}

}  // namespace coxmesh
