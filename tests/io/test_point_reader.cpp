// Point-cloud readers: every format read back, and every kind of bad input rejected with one clear
// InputError naming the file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "coxmesh/io/point_reader.h"
#include "coxmesh/lattice/simplex.h"

using namespace coxmesh;
namespace fs = std::filesystem;

namespace {

class PointReader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("coxmesh_points_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& content) {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << content;
    return p.string();
  }
  // Expects read_points(path) to throw an InputError whose message holds `part` and the path.
  void rejects(const std::string& path, const std::string& part, const PointReadOptions& o = {}) {
    try {
      read_points(path, o);
      ADD_FAILURE() << path << ": no error, expected '" << part << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(fs::path(path).filename().string()), std::string::npos) << e.what();
    }
  }
  fs::path dir_;
};

template <class T>
std::string bytes(std::initializer_list<T> values) {
  std::string out;
  for (T v : values) out.append(reinterpret_cast<const char*>(&v), sizeof v);
  return out;
}

std::string npy(const std::string& descr, const std::string& shape, const std::string& data, bool fortran = false) {
  std::string header =
      "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") + ", 'shape': " + shape + ", }";
  while ((10 + header.size() + 1) % 64) header += ' ';
  header += '\n';
  std::string out = "\x93NUMPY";
  out += '\x01';
  out += '\x00';
  out += static_cast<char>(header.size() & 0xFF);
  out += static_cast<char>(header.size() >> 8);
  return out + header + data;
}

TEST_F(PointReader, RowsOfNumbers) {
  PointSet s = read_points(write("a.xyz", "# three points\n0 0 0\n1 0 0  # trailing comment\n\n0 1 +2.5e-1\n"));
  EXPECT_EQ(s.dimension, 3);
  EXPECT_EQ(s.points, (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0.25}));
  EXPECT_TRUE(s.normals.empty());
  EXPECT_EQ(s.format, "xyz");
  s = read_points(write("b.xyz", "0 0 0 0 0 1\n1 0 0 1 0 0\n"));  // x y z nx ny nz
  EXPECT_EQ(s.dimension, 3);
  EXPECT_EQ(s.normals, (std::vector<double>{0, 0, 1, 1, 0, 0}));
  PointReadOptions six;
  six.dimension = 6;
  EXPECT_EQ(read_points(write("c.xyz", "0 0 0 0 0 1\n1 0 0 1 0 0\n"), six).dimension, 6);
  s = read_points(write("d.txt", "1 2 3 4 5\n6 7 8 9 10\n"));  // any d
  EXPECT_EQ(s.dimension, 5);
  EXPECT_EQ(s.size(), 2u);
  s = read_points(write("e.csv", "x, y,z\n1,2,3\n4, 5 ,6\n"));  // header skipped
  EXPECT_EQ(s.points, (std::vector<double>{1, 2, 3, 4, 5, 6}));
  s = read_points(write("f.CSV", "1,2\n3,4\n"));  // no header; extension case ignored
  EXPECT_EQ(s.dimension, 2);
}

TEST_F(PointReader, Off) {
  PointSet s = read_points(write("a.off", "OFF\n# comment\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_EQ(s.size(), 3u);
  EXPECT_EQ(s.points[3], 1);
  s = read_points(write("b.off", "OFF 2 0 0\n0 0 0\n1 1 1\n"));  // counts on the first line
  EXPECT_EQ(s.size(), 2u);
  s = read_points(write("c.off", "NOFF\n2 0 0\n0 0 0 0 0 1\n1 1 1 1 0 0\n"));
  EXPECT_EQ(s.normals, (std::vector<double>{0, 0, 1, 1, 0, 0}));
  s = read_points(write("d.off", "COFF\n2 0 0\n0 0 0 255 0 0 255\n1 1 1 0 255 0 255\n"));  // colours ignored
  EXPECT_EQ(s.points, (std::vector<double>{0, 0, 0, 1, 1, 1}));
  s = read_points(write("e.off", "nOFF\n4\n2 0 0\n1 2 3 4\n5 6 7 8\n"));
  EXPECT_EQ(s.dimension, 4);
  EXPECT_EQ(s.points.back(), 8);
}

TEST_F(PointReader, PlyAscii) {
  const std::string ply =
      "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty uchar red\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 0 0 1 255\n1 0 0 0 0 1 0\n0 1 0 0 0 1 7\n3 0 1 2\n";
  const PointSet s = read_points(write("a.ply", ply));
  EXPECT_EQ(s.points, (std::vector<double>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
  EXPECT_EQ(s.normals.size(), 9u);
  EXPECT_EQ(s.normals[2], 1);
}

TEST_F(PointReader, PlyBinary) {
  // An element before the vertices (with a list), float coordinates, a double property ignored,
  // then faces.
  std::string body = bytes<std::uint8_t>({2}) + bytes<std::int32_t>({7, 8});  // "extra": one list
  body += bytes<float>({0, 0, 0}) + bytes<double>({1.5}) + bytes<float>({2, 0, 0}) + bytes<double>({2.5});
  body += bytes<std::uint8_t>({3}) + bytes<std::int32_t>({0, 1, 0});
  const std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement extra 1\nproperty list uchar int ids\nelement vertex 2\n"
      "property float x\nproperty float y\nproperty float z\nproperty double quality\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n" +
      body;
  const PointSet s = read_points(write("b.ply", ply));
  EXPECT_EQ(s.points, (std::vector<double>{0, 0, 0, 2, 0, 0}));
  EXPECT_TRUE(s.normals.empty());
}

TEST_F(PointReader, Npy) {
  PointSet s = read_points(write("a.npy", npy("<f8", "(2, 4)", bytes<double>({1, 2, 3, 4, 5, 6, 7, 8}))));
  EXPECT_EQ(s.dimension, 4);
  EXPECT_EQ(s.points.back(), 8);
  s = read_points(write("b.npy", npy("<f4", "(3, 2)", bytes<float>({1, 2, 3, 4, 5, 6.5f}))));
  EXPECT_EQ(s.dimension, 2);
  EXPECT_EQ(s.points.back(), 6.5);
}

TEST_F(PointReader, Duplicates) {
  // Exact duplicates are removed, the first occurrence kept, the order otherwise unchanged.
  const PointSet s = read_points(write("d.xyz", "1 0 0\n0 1 0\n1 0 0\n0 0 1\n0 1 0\n1 0 0\n"));
  EXPECT_EQ(s.duplicates, 3u);
  EXPECT_EQ(s.points, (std::vector<double>{1, 0, 0, 0, 1, 0, 0, 0, 1}));
}

TEST_F(PointReader, BadInput) {
  rejects(write("nan.xyz", "0 0 0\n1 nan 0\n"), "line 2: NaN");
  rejects(write("inf.csv", "1,2,3\n4,inf,6\n"), "infinite");
  rejects(write("word.txt", "1 2 3\n4 x 6\n"), "'x' is not a number");
  rejects(write("ragged.txt", "1 2 3\n4 5\n"), "line 2 has 2 numbers, line 1 has 3");
  rejects(write("empty.xyz", "# nothing\n\n"), "no points");
  rejects(write("wrongdim.xyz", "1 2 3\n"), "expected R^4", PointReadOptions{4});
  rejects(write(
              "wide.txt", std::string(40 * 2, ' ') + "\n" +
                              [] {
                                std::string r;
                                for (int i = 0; i < 40; ++i) r += "1 ";
                                return r;
                              }() +
                              "\n"),
          "d must be between 1 and 31");
  rejects(write("huge.off", "OFF\n1000000000 0 0\n0 0 0\n"), "more than the file can hold");
  rejects(write("short.off", "OFF\n3 0 0\n0 0 0\n1 1 1\n# a comment long enough\n"), "ends after 2 of 3 vertices");
  rejects(write("bad.off", "PLY\n"), "expected OFF");
  rejects(write("huge.ply",
                "ply\nformat binary_little_endian 1.0\nelement vertex 100000000\nproperty float x\nproperty float y\n"
                "property float z\nend_header\n" +
                    bytes<float>({0, 0, 0})),
          "more than the file can hold");
  rejects(write("big.ply",
                "ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                "property float z\nend_header\n" +
                    bytes<float>({0, 0, 0})),
          "big-endian");
  rejects(write("noz.ply",
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n"),
          "lacks x, y or z");
  rejects(write("cut.ply",
                "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                "end_header\n0 0 0\n\n\n\n\n\n\n"),
          "ends inside the vertex element");
  rejects(write("nan.ply",
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                "end_header\n0 nan 0\n"),
          "NaN");
  rejects(write("size.npy", npy("<f8", "(3, 4)", bytes<double>({1, 2}))), "announces 3 x 4 values");
  rejects(write("int.npy", npy("<i4", "(1, 2)", bytes<std::int32_t>({1, 2}))), "only float64");
  rejects(write("fortran.npy", npy("<f8", "(1, 2)", bytes<double>({1, 2}), true)), "Fortran");
  rejects(write("rank.npy", npy("<f8", "(4,)", bytes<double>({1, 2, 3, 4}))), "shape (n, d)");
  rejects(write("nan.npy", npy("<f8", "(1, 2)", bytes<double>({1, std::nan("")}))), "NaN");
  rejects(write("magic.npy", "not numpy at all"), "bad magic");
  rejects(write("points.las", "1 2 3\n"), "unknown point file extension '.las'");
  rejects((dir_ / "missing.xyz").string(), "cannot open");
  fs::create_directories(dir_ / "folder.xyz");
  rejects((dir_ / "folder.xyz").string(), "is a directory");
}

}  // namespace
