// The native format with manifolds with corners (version 2): the bitmasks round-trip exactly, and
// the reader rejects bitmasks that contradict the keys, the domain count or the facets.
#include <gtest/gtest.h>

#include <cstring>
#include <sstream>

#include "coxmesh/cell_complex/topology.h"
#include "coxmesh/io/native_format.h"
#include "coxmesh/io/write_mesh.h"
#include "coxmesh/tracing/trace_strata.h"

using namespace coxmesh;

namespace {

// The octant x, y, z > 0 of the unit sphere: three faces, three corners.
CellComplex octant() {
  const Triangulation t = Triangulation::coxeter(3).with_longest_edge(0.3).rotated(4);
  StratifiedOracle oracle(
      t, sphere(2, 3, 1.0),
      {half_space_domain({-1, 0, 0}, 0), half_space_domain({0, -1, 0}, 0), half_space_domain({0, 0, -1}, 0)});
  return build_stratified_cell_complex(trace_strata(t, oracle, {{0.577, 0.577, 0.577}}));
}

NativeFile read(const std::string& bytes) {
  std::stringstream in(bytes);
  return read_native(in, "corners.cxm");
}

// Replaces the first occurrence of `from` (same length) in `bytes`.
std::string replaced(std::string bytes, const std::string& from, const std::string& to) {
  const std::size_t at = bytes.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  EXPECT_EQ(from.size(), to.size());
  return at == std::string::npos ? bytes : bytes.replace(at, from.size(), to);
}

TEST(NativeCorners, RoundTripKeepsTheStrata) {
  const CellComplex cc = octant();
  std::stringstream buffer;
  write_native(buffer, cc);
  const std::string bytes = buffer.str();
  EXPECT_NE(bytes.find("\"version\":2"), std::string::npos);
  const CellComplex back = read(bytes).cells;
  EXPECT_EQ(back.domain_count, 3);
  ASSERT_EQ(back.interior.size(), cc.interior.size());
  for (std::size_t j = 0; j < cc.interior.size(); ++j) {
    const CellLevel &a = cc.interior[j], &b = back.interior[j];
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(0, std::memcmp(a.simplices.key(0), b.simplices.key(0), 4ull * a.size() * a.simplices.words()));
    EXPECT_EQ(a.domains, b.domains);
    EXPECT_EQ(a.facet_ids, b.facet_ids);
  }
  EXPECT_EQ(cc.vertices, back.vertices);
  const TopologyReport t = analyze_topology(back);
  EXPECT_TRUE(t.is_manifold) << t.manifold_problem;
  EXPECT_EQ(t.euler_characteristic, 1);
  std::size_t corners = 0;
  for (const StratumCount& s : stratum_counts(back)) corners += s.domains != 0 && s.dimension == 0 ? s.cells[0] : 0;
  EXPECT_EQ(corners, 3u);
  std::stringstream again;
  write_native(again, back);
  EXPECT_EQ(again.str(), bytes);
}

TEST(NativeCorners, RejectsInconsistentStrata) {
  const CellComplex cc = octant();
  std::stringstream buffer;
  write_native(buffer, cc);
  const std::string bytes = buffer.str();
  EXPECT_THROW(read(replaced(bytes, "\"version\":2", "\"version\":3")), InputError);
  EXPECT_THROW(read(replaced(bytes, "\"domains\":3", "\"domains\":1")), InputError);  // bits beyond the count
  EXPECT_THROW(read(replaced(bytes, "\"domains\":3", "\"domains\":0")), InputError);  // keys of the wrong width
  EXPECT_THROW(read(replaced(bytes, "\"domains\":true", "\"domains\":fals")), InputError);
  // The bitmask array of level 0 (after its keys and offsets) against its keys: change one mask.
  const std::size_t header_end = bytes.find('\n') + 1, n0 = cc.interior[0].size();
  const std::size_t masks = header_end + 4 * (n0 * stratum_key_words(3) + n0 + 1);
  std::string bad = bytes;
  bad[masks] ^= 1;
  EXPECT_THROW(read(bad), InputError);
  // A key whose stratum needs a simplex of another dimension: a vertex cell of the interior
  // claiming a domain.
  bad = bytes;
  bad[header_end + 4 * packed_words(3)] ^= 1;
  EXPECT_THROW(read(bad), InputError);
}

TEST(NativeCorners, OtherFormatsRefuseWhatTheyCannotHold) {
  const CellComplex cc = octant();
  EXPECT_NO_THROW(check_stratified_format(MeshFormat::vtu, 3));
  EXPECT_NO_THROW(check_stratified_format(MeshFormat::cxm, 3));
  EXPECT_NO_THROW(check_stratified_format(MeshFormat::ply, 2));
  EXPECT_THROW(check_stratified_format(MeshFormat::stl, 3), InputError);
  EXPECT_THROW(check_stratified_format(MeshFormat::msh, 2), InputError);
  EXPECT_THROW(write_mesh("/nonexistent/x.mesh", MeshFormat::medit, cc), InputError);
}

}  // namespace
