// Two traces are identical: the same S and S_∂ in the same order, the same point bits, the same status.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "coxmesh/tracing/trace_manifold.h"

inline void expect_identical(const coxmesh::TraceResult& a, const coxmesh::TraceResult& b, const std::string& what) {
  ASSERT_EQ(a.simplices.size(), b.simplices.size()) << what;
  ASSERT_EQ(a.boundary_simplices.size(), b.boundary_simplices.size()) << what;
  const int w = a.simplices.words();
  for (std::uint32_t i = 0; i < a.simplices.size(); ++i)
    ASSERT_EQ(std::memcmp(a.simplices.key(i), b.simplices.key(i), 4 * w), 0) << what << " simplex " << i;
  // Every simplex is found in b's index under its id (the parallel walk indexes S after the fact).
  ASSERT_EQ(b.simplices.unindexed(), 0u) << what;
  for (std::uint32_t i = 0; i < b.simplices.size(); ++i) ASSERT_EQ(b.simplices.find(b.simplices.key(i)), i) << what;
  for (std::uint32_t i = 0; i < a.boundary_simplices.size(); ++i)
    ASSERT_EQ(std::memcmp(a.boundary_simplices.key(i), b.boundary_simplices.key(i), 4 * w), 0) << what;
  // Bitwise equality of the points (memcmp would be passed null for empty vectors).
  auto same_bits = [](const coxmesh::PointArray& x, const coxmesh::PointArray& y) {
    return x.size() == y.size() && (x.empty() || std::memcmp(x.data(), y.data(), 8 * x.size()) == 0);
  };
  EXPECT_TRUE(same_bits(a.points, b.points)) << what;
  EXPECT_TRUE(same_bits(a.boundary_points, b.boundary_points)) << what;
  EXPECT_EQ(a.status, b.status) << what;
}
