// mesh_point_cloud: the oracle chosen for the samples (the winding oracle only for a non-orientable
// normal bundle in codimension 2 and nothing but the tube bounding the walk), each oracle's
// pipeline, the samples as seeds, and bad combinations as InputError.
#include <gtest/gtest.h>

#include "../oracle/point_samples.h"
#include "coxmesh/io/point_cloud_report.h"
#include "coxmesh/mesh/mesh_point_cloud.h"
#include "coxmesh/oracle/implicit_function.h"

using namespace coxmesh;

namespace {

PreparedPointCloud prepared(const std::string& name, std::size_t n, SampleOracle oracle = SampleOracle::automatic,
                            bool other_bounds = false) {
  const test::Samples s = test::sample_manifold(name, n);
  PointCloudMeshOptions o;
  o.m = s.m;
  o.oracle = oracle;
  o.other_bounds = other_bounds;
  return prepare_samples(s.points, s.d, SampleSource{"", "array", s.size(), 0}, o);
}

Triangulation triangulation(const PreparedPointCloud& pc) {
  return Triangulation::coxeter(pc.problem.diagnostics.ambient_dimension)
      .with_longest_edge(pc.problem.edge_length)
      .with_offset(pc.problem.centre());
}

}  // namespace

TEST(MeshPointCloud, OrientableSamplesGetTheVertexOracle) {
  const PreparedPointCloud pc = prepared("torus", 3000);
  EXPECT_EQ(pc.oracle, SampleOracle::vertex);
  EXPECT_FALSE(pc.oracle_chosen);
  const PointCloudMeshReport r = mesh_point_cloud(triangulation(pc), pc, {});
  EXPECT_EQ(r.mesh.topology.betti, (std::vector<std::size_t>{1, 2, 1}));
  EXPECT_TRUE(r.mesh.topology.is_manifold);
  EXPECT_EQ(r.mesh.automatic_seeds, pc.problem.seeds.size());
  EXPECT_FALSE(r.counts.winding_odd_tetrahedra || r.counts.local_pca_defects);
  const nlohmann::json j = point_cloud_json(pc, r.counts);
  EXPECT_EQ(j["oracle"], "vertex");
  EXPECT_TRUE(j["file"].is_null());
  EXPECT_FALSE(j.contains("oracle_reason"));
}

TEST(MeshPointCloud, NonOrientableNormalBundleGetsTheWindingOracle) {
  const PreparedPointCloud pc = prepared("rp2", 3000);
  ASSERT_EQ(pc.oracle, SampleOracle::winding);
  EXPECT_TRUE(pc.oracle_chosen);
  EXPECT_TRUE(pc.warnings().empty());  // (the winding oracle meshes what it is about)
  const PointCloudMeshReport r = mesh_point_cloud(triangulation(pc), pc, {});
  EXPECT_EQ(r.mesh.topology.betti, (std::vector<std::size_t>{1, 1, 1}));
  ASSERT_TRUE(r.counts.winding_odd_tetrahedra);
  EXPECT_EQ(*r.counts.winding_odd_tetrahedra, 0u);
  EXPECT_EQ(point_cloud_json(pc, r.counts)["oracle_reason"], pc.oracle_reason());

  // With another bound the per-vertex function stays, and warns.
  const PreparedPointCloud bounded = prepared("rp2", 3000, SampleOracle::automatic, true);
  EXPECT_EQ(bounded.oracle, SampleOracle::vertex);
  EXPECT_EQ(bounded.warnings().size(), 1u);
}

TEST(MeshPointCloud, OraclesWithoutFTakeOnlyTheTube) {
  const PreparedPointCloud pc = prepared("sphere", 1000, SampleOracle::local_pca);
  MeshOptions with_box;
  with_box.search_box = pc.problem.box;
  EXPECT_THROW(mesh_point_cloud(triangulation(pc), pc, with_box), InputError);
  MeshOptions refined;
  refined.refine = true;
  EXPECT_THROW(mesh_point_cloud(triangulation(pc), pc, refined), InputError);
  const PointCloudMeshReport r = mesh_point_cloud(triangulation(pc), pc, {});
  EXPECT_TRUE(r.counts.local_pca_defects.has_value());
  const PreparedPointCloud winding = prepared("sphere", 1000, SampleOracle::winding);
  EXPECT_THROW(mesh_point_cloud(triangulation(winding), winding, {}), InputError);  // codimension 1
  EXPECT_THROW(sample_oracle_named("nearest"), InputError);
  EXPECT_EQ(sample_oracle_named(sample_oracle_name(SampleOracle::local_pca)), SampleOracle::local_pca);
}

TEST(MeshPointCloud, ArraysAreCheckedAsFilesAre) {
  EXPECT_THROW(point_set_from_rows({0, 0, 1, std::nan(""), 2, 2}, 2), InputError);
  EXPECT_THROW(point_set_from_rows({0, 0, 1}, 2), InputError);
  EXPECT_THROW(point_set_from_rows({0, 0, 1, 1}, 2, {1, 0}), InputError);
  const PointSet set = point_set_from_rows({0, 0, 1, 1, 0, 0}, 2);
  EXPECT_EQ(set.size(), 2u);
  EXPECT_EQ(set.duplicates, 1u);
  EXPECT_EQ(set.format, "array");
}
