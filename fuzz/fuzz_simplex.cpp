// The simplex text form "(y) [{..},{..}]", then the faces and cofaces of what it accepts (when few
// enough to list), checked against the face relation, the coface count and the text round trip.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "coxmesh/lattice/cofaces.h"
#include "coxmesh/lattice/faces.h"

using namespace coxmesh;

namespace {
void check(bool ok) {
  if (!ok) std::abort();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Simplex s;
  try {
    s = parse_simplex(std::string_view(reinterpret_cast<const char*>(data), size));
  } catch (const InputError&) {
    return 0;
  }
  check(s.d >= 1 && s.d <= kMaxDimension && s.k <= s.d);
  check(parse_simplex(to_string(s)) == s);
  std::uint32_t key[packed_words(kMaxDimension)];
  pack(s, key);
  check(unpack(key, s.d) == s);
  // Faces: 2^(k+1) − 1 of them in all; listed up to k = 12.
  if (s.k <= 12)
    for (int j = 0; j <= s.k; ++j) {
      FaceEnumerator faces(s, j);
      for (Simplex f; faces.next(f);) check(f.k == j && is_face_of(f, s));
    }
  // Cofaces: up to (d + 1)! of them; listed only where there are few.
  for (int l = s.k; l <= s.d; ++l) {
    std::uint64_t count = 0;
    try {
      count = coface_count(s, l);
    } catch (const InputError&) {
      continue;  // more than 2^64
    }
    if (count > 5000) continue;
    std::uint64_t seen = 0;
    CofaceEnumerator cofaces(s, l);
    while (const Simplex* mu = cofaces.next()) {
      check(mu->k == l && is_face_of(s, *mu));
      ++seen;
    }
    check(seen == count);
  }
  return 0;
}
