// VTK output: the tube geometry follows the section directors, the .vtp document is well formed with
// consistent counts and arrays, and the .pvd collection lists the files written.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

#include "nodus/beam/strain_measures.hpp"
#include "nodus/output/vtk_format.hpp"
#include "nodus/output/vtk_series.hpp"
#include "nodus/output/vtk_xml.hpp"
#include "output_test_support.hpp"

namespace nodus::output {
namespace {

using testing::ScratchDir;

constexpr int kSides = 7;

TEST(TubeMesh, CountsAndRingRadiusInReference) {
  const model::Model m = testing::two_beam_model();
  const TubeMesh mesh = tube_mesh(m, m.reference(), kSides);
  ASSERT_EQ(mesh.points.cols(), m.num_nodes() * (1 + kSides));
  EXPECT_EQ(mesh.line_offsets.size(), m.beams().size());
  EXPECT_EQ(mesh.line_connectivity.size(), static_cast<std::size_t>(m.num_nodes()));
  std::size_t quads = 0;
  for (const beam::Beam& b : m.beams()) quads += static_cast<std::size_t>((b.num_nodes() - 1) * kSides);
  EXPECT_EQ(mesh.poly_offsets.size(), quads);
  EXPECT_EQ(mesh.poly_connectivity.size(), 4 * quads);
  EXPECT_EQ(mesh.poly_offsets.back(), static_cast<std::int64_t>(mesh.poly_connectivity.size()));

  for (const beam::Beam& b : m.beams()) {
    for (int i = 0; i < b.num_nodes(); ++i) {
      const int n = b.node(i);
      const Eigen::Vector3d centre = m.reference().segment<3>(9 * n);
      EXPECT_LT((mesh.points.col(n) - centre).norm(), 1e-14);
      for (int j = 0; j < kSides; ++j) {
        const Eigen::Vector3d p = mesh.points.col(ring_point_index(m.num_nodes(), kSides, n, j));
        EXPECT_NEAR((p - centre).norm(), b.radius(), 1e-13);
        EXPECT_NEAR((p - centre).dot(b.definition().direction), 0.0, 1e-13);  // in the section plane
        EXPECT_EQ(mesh.point_node[static_cast<std::size_t>(ring_point_index(m.num_nodes(), kSides, n, j))],
                  n);
      }
    }
  }
}

TEST(TubeMesh, QuadsFaceOutwards) {
  const model::Model m = testing::two_beam_model();
  const TubeMesh mesh = tube_mesh(m, m.reference(), kSides);
  for (std::size_t q = 0; q < mesh.poly_offsets.size(); ++q) {
    const std::int64_t* v = &mesh.poly_connectivity[4 * q];
    const Eigen::Vector3d a = mesh.points.col(v[0]), b = mesh.points.col(v[1]), c = mesh.points.col(v[2]);
    const Eigen::Vector3d normal = (b - a).cross(c - b);
    const int node = mesh.point_node[static_cast<std::size_t>(v[0])];
    const Eigen::Vector3d outward = (a + b) / 2 - m.reference().segment<3>(9 * node);
    EXPECT_GT(normal.dot(outward), 0.0) << "quad " << q;
  }
}

TEST(TubeMesh, RingFollowsCurrentUnnormalisedDirectors) {
  const model::Model m = testing::two_beam_model();
  const Eigen::VectorXd x = testing::deformed_state(m);
  const TubeMesh mesh = tube_mesh(m, x, kSides);
  for (const beam::Beam& b : m.beams())
    for (int i = 0; i < b.num_nodes(); ++i) {
      const int n = b.node(i);
      for (int j = 0; j < kSides; ++j) {
        const double phi = 2 * std::numbers::pi * j / kSides;
        const Eigen::Vector3d expected =
            x.segment<3>(9 * n) +
            b.radius() * (std::cos(phi) * x.segment<3>(9 * n + 3) + std::sin(phi) * x.segment<3>(9 * n + 6));
        EXPECT_LT((mesh.points.col(ring_point_index(m.num_nodes(), kSides, n, j)) - expected).norm(), 1e-13);
      }
    }
}

TEST(TubeMesh, RejectsBadInput) {
  const model::Model m = testing::two_beam_model();
  EXPECT_THROW(tube_mesh(m, m.reference(), 2), std::invalid_argument);
  EXPECT_THROW(tube_mesh(m, Eigen::VectorXd::Zero(3), kSides), std::invalid_argument);
}

/// The tests that read a document back, in either encoding.
class VtpIn : public ::testing::TestWithParam<VtkEncoding> {};

INSTANTIATE_TEST_SUITE_P(Encodings, VtpIn, ::testing::Values(VtkEncoding::binary, VtkEncoding::ascii),
                         [](const auto& info) {
                           return info.param == VtkEncoding::binary ? "binary" : "ascii";
                         });

TEST_P(VtpIn, DocumentIsWellFormedWithConsistentCounts) {
  const model::Model m = testing::two_beam_model();
  const Eigen::VectorXd x = testing::deformed_state(m);
  ScratchDir dir;
  const auto path = dir.path() / "state.vtp";
  write_vtp(path, m, x, kSides, 0.25, GetParam());
  const auto root = testing::parse_vtk(testing::read_text(path));

  ASSERT_EQ(root->name, "VTKFile");
  EXPECT_EQ(root->attribute("type"), "PolyData");
  EXPECT_EQ(root->attribute("version"), GetParam() == VtkEncoding::binary ? "1.0" : "0.1");
  EXPECT_EQ(root->attribute("byte_order"), "LittleEndian");
  const testing::XmlElement& poly = root->one("PolyData");
  EXPECT_DOUBLE_EQ(testing::numbers(poly.one("FieldData").data_array("TimeValue").text).at(0), 0.25);
  const testing::XmlElement& piece = poly.one("Piece");
  const int num_points = m.num_nodes() * (1 + kSides);
  const TubeMesh mesh = tube_mesh(m, x, kSides);
  EXPECT_EQ(std::stoi(piece.attribute("NumberOfPoints")), num_points);
  EXPECT_EQ(piece.attribute("NumberOfVerts"), "0");
  EXPECT_EQ(piece.attribute("NumberOfStrips"), "0");
  EXPECT_EQ(std::stoul(piece.attribute("NumberOfLines")), m.beams().size());
  EXPECT_EQ(std::stoul(piece.attribute("NumberOfPolys")), mesh.poly_offsets.size());

  // Points, read back, equal the tube geometry (centres first, then the rings).
  const auto points = testing::numbers(piece.one("Points").one("DataArray").text);
  ASSERT_EQ(points.size(), static_cast<std::size_t>(3 * num_points));
  for (int p = 0; p < num_points; ++p)
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(points[static_cast<std::size_t>(3 * p + k)], mesh.points(k, p), 1e-10);

  // Point data: every array has one tuple per point; ring points repeat their node's values.
  const testing::XmlElement& data = piece.one("PointData");
  std::set<std::string> names;
  for (const testing::XmlElement* a : data.all("DataArray")) {
    const std::string name = a->attribute("Name");
    names.insert(name);
    const int components =
        a->attributes.count("NumberOfComponents") ? std::stoi(a->attribute("NumberOfComponents")) : 1;
    const auto values = testing::numbers(a->text);
    ASSERT_EQ(values.size(), static_cast<std::size_t>(components * num_points)) << name;
    for (int n = 0; n < m.num_nodes(); ++n)
      for (int j = 0; j < kSides; ++j)
        for (int c = 0; c < components; ++c)
          EXPECT_EQ(values[static_cast<std::size_t>(
                        components * ring_point_index(m.num_nodes(), kSides, n, j) + c)],
                    values[static_cast<std::size_t>(components * n + c)])
              << name;
  }
  for (const char* expected : {"beam", "node", "g1", "g2", "displacement"})
    EXPECT_TRUE(names.count(expected)) << expected;
  for (int k = 0; k < beam::kNumStrains; ++k)
    EXPECT_TRUE(names.count(beam::strain_name(k))) << beam::strain_name(k);
  EXPECT_EQ(data.data_array("beam").attribute("type"), "Int32");
  EXPECT_EQ(data.data_array("node").attribute("type"), "Int32");
  EXPECT_EQ(data.data_array("g1").attribute("NumberOfComponents"), "3");

  const auto beam_ids = testing::numbers(data.data_array("beam").text);
  const auto node_ids = testing::numbers(data.data_array("node").text);
  for (int b = 0; b < 2; ++b)
    for (int i = 0; i < m.beam(b).num_nodes(); ++i) {
      EXPECT_EQ(beam_ids[static_cast<std::size_t>(m.beam(b).node(i))], b);
      EXPECT_EQ(node_ids[static_cast<std::size_t>(m.beam(b).node(i))], m.beam(b).node(i));
    }
  const auto strains = m.node_strains(x);
  const auto e33 = testing::numbers(data.data_array(beam::strain_name(beam::kE33)).text);
  for (int n = 0; n < m.num_nodes(); ++n)
    EXPECT_NEAR(e33[static_cast<std::size_t>(n)], strains(beam::kE33, n),
                1e-10 * (1 + std::abs(strains(beam::kE33, n))));
  const auto g2 = testing::numbers(data.data_array("g2").text);
  for (int n = 0; n < m.num_nodes(); ++n)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(g2[static_cast<std::size_t>(3 * n + c)], x[9 * n + 6 + c], 1e-11);

  // Cells: offsets end at the connectivity size, indices within the points.
  for (const char* cells : {"Lines", "Polys"}) {
    const testing::XmlElement& c = piece.one(cells);
    const auto connectivity = testing::numbers(c.data_array("connectivity").text);
    const auto offsets = testing::numbers(c.data_array("offsets").text);
    ASSERT_FALSE(offsets.empty()) << cells;
    EXPECT_EQ(offsets.back(), static_cast<double>(connectivity.size())) << cells;
    for (double v : connectivity) {
      EXPECT_GE(v, 0);
      EXPECT_LT(v, num_points);
    }
  }
  EXPECT_EQ(std::stoul(piece.attribute("NumberOfPolys")),
            testing::numbers(piece.one("Polys").data_array("offsets").text).size());
  // The centreline of beam b runs through its node centres, which are the first points.
  const auto line = testing::numbers(piece.one("Lines").data_array("connectivity").text);
  for (int n = 0; n < m.num_nodes(); ++n) EXPECT_EQ(line[static_cast<std::size_t>(n)], n);
}

TEST_P(VtpIn, ReferenceRingsReadBackAtBeamRadius) {
  const model::Model m = testing::two_beam_model();
  ScratchDir dir;
  write_vtp(dir.path() / "ref.vtp", m, m.reference(), kSides, std::nullopt, GetParam());
  const auto root = testing::parse_vtk(testing::read_text(dir.path() / "ref.vtp"));
  const testing::XmlElement& piece = root->one("PolyData").one("Piece");
  EXPECT_TRUE(root->one("PolyData").all("FieldData").empty());
  const auto points = testing::numbers(piece.one("Points").one("DataArray").text);
  for (const beam::Beam& b : m.beams())
    for (int i = 0; i < b.num_nodes(); ++i) {
      const int n = b.node(i);
      const Eigen::Vector3d centre(points[3 * n], points[3 * n + 1], points[3 * n + 2]);
      for (int j = 0; j < kSides; ++j) {
        const auto p = static_cast<std::size_t>(3 * ring_point_index(m.num_nodes(), kSides, n, j));
        EXPECT_NEAR((Eigen::Vector3d(points[p], points[p + 1], points[p + 2]) - centre).norm(), b.radius(),
                    1e-10);
      }
    }
}

// The appended arrays of a binary file, decoded by the test's own reader: whole blocks of 32 KiB and a
// partial last one, an exact multiple of the block (its last size 0), and an empty array.
TEST(CompressedArray, BlocksAreThoseVtkReads) {
  const auto header = [](const std::string& bytes, int i) {
    std::uint64_t w = 0;
    std::memcpy(&w, bytes.data() + 8 * i, 8);
    return w;
  };
  for (const std::size_t count : {std::size_t{100000}, std::size_t{4096}, std::size_t{1}}) {
    std::vector<double> values(count);
    for (std::size_t i = 0; i < count; ++i)
      values[i] = std::sin(0.001 * static_cast<double>(i)) * 1e3 + 0.5 * i;
    const std::string bytes = vtk_xml::compressed_array(values.data(), count * sizeof(double));
    const std::uint64_t size = count * sizeof(double);
    EXPECT_EQ(header(bytes, 0), (size + 32767) / 32768) << count;
    EXPECT_EQ(header(bytes, 1), 32768u);
    EXPECT_EQ(header(bytes, 2), size % 32768) << count;
    EXPECT_EQ(testing::decode_appended<double>(bytes, 0), values) << count;
    // Smaller than the values themselves (a smooth series compresses).
    if (count > 1) EXPECT_LT(bytes.size(), size) << count;
  }
  const std::string empty = vtk_xml::compressed_array(nullptr, 0);
  EXPECT_EQ(empty.size(), 24u);
  EXPECT_EQ(header(empty, 0), 0u);
  EXPECT_TRUE(testing::decode_appended<double>(empty, 0).empty());
}

// Both encodings hold the same values: the ASCII file's 12 significant digits against the binary file's
// exact ones.
TEST(Vtp, BinaryAndAsciiHoldTheSameArrays) {
  const model::Model m = testing::two_beam_model();
  const Eigen::VectorXd x = testing::deformed_state(m);
  std::ostringstream binary, ascii;
  write_vtp(binary, m, x, kSides, 0.5, VtkEncoding::binary);
  write_vtp(ascii, m, x, kSides, 0.5, VtkEncoding::ascii);
  EXPECT_EQ(binary.str().find("format=\"ascii\">\n"), std::string::npos);  // only TimeValue is inline
  const auto b = testing::parse_vtk(binary.str());
  const auto a = testing::parse_vtk(ascii.str());
  const testing::XmlElement& pb = b->one("PolyData").one("Piece");
  const testing::XmlElement& pa = a->one("PolyData").one("Piece");
  int arrays = 0;
  for (const char* section : {"PointData", "Points", "Lines", "Polys"}) {
    const auto in_b = pb.one(section).all("DataArray");
    const auto in_a = pa.one(section).all("DataArray");
    ASSERT_EQ(in_b.size(), in_a.size()) << section;
    for (std::size_t k = 0; k < in_b.size(); ++k, ++arrays) {
      const std::string& name = in_b[k]->attribute("Name");
      EXPECT_EQ(name, in_a[k]->attribute("Name"));
      EXPECT_EQ(in_b[k]->attribute("type"), in_a[k]->attribute("type")) << name;
      const auto vb = testing::numbers(in_b[k]->text);
      const auto va = testing::numbers(in_a[k]->text);
      ASSERT_EQ(vb.size(), va.size()) << name;
      for (std::size_t i = 0; i < vb.size(); ++i)
        ASSERT_NEAR(vb[i], va[i], 1e-11 * (1 + std::abs(vb[i]))) << name;
    }
  }
  EXPECT_EQ(arrays, 5 + beam::kNumStrains + 1 + 4);
}

TEST(Pvd, SeriesListsTheFilesWritten) {
  const model::Model m = testing::two_beam_model();
  const Eigen::VectorXd x = testing::deformed_state(m);
  ScratchDir dir;
  // A file of an earlier run is removed by begin(); other files are kept.
  std::filesystem::create_directories(dir.path() / "vtk");
  write_vtp(dir.path() / "vtk" / "step_000099.vtp", m, x, kSides);
  write_vtp(dir.path() / "vtk" / "mine.vtp", m, x, kSides);

  VtkSeries series(dir.path(), kSides);
  series.begin();
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "vtk" / "step_000099.vtp"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "vtk" / "mine.vtp"));
  EXPECT_TRUE(testing::parse_xml(testing::read_text(series.pvd_path()))->one("Collection").children.empty());

  series.write(0, 0.0, m, m.reference());
  series.write(3, 0.375, m, x);
  series.write(12, 1.5, m, x);
  series.write(12, 1.5, m, x);  // again: replaces, no second entry
  EXPECT_TRUE(series.written(3));
  EXPECT_FALSE(series.written(4));

  const auto root = testing::parse_xml(testing::read_text(dir.path() / "result.pvd"));
  EXPECT_EQ(root->attribute("type"), "Collection");
  const auto sets = root->one("Collection").all("DataSet");
  ASSERT_EQ(sets.size(), 3u);
  const std::vector<std::pair<std::string, double>> expected{
      {"vtk/step_000000.vtp", 0.0}, {"vtk/step_000003.vtp", 0.375}, {"vtk/step_000012.vtp", 1.5}};
  for (std::size_t i = 0; i < sets.size(); ++i) {
    EXPECT_EQ(sets[i]->attribute("file"), expected[i].first);
    EXPECT_DOUBLE_EQ(std::stod(sets[i]->attribute("timestep")), expected[i].second);
    EXPECT_TRUE(std::filesystem::exists(dir.path() / expected[i].first)) << expected[i].first;
    EXPECT_NO_THROW(testing::parse_vtk(testing::read_text(dir.path() / expected[i].first)));
  }
  // No temporary files are left behind.
  for (const auto& folder : {dir.path(), dir.path() / "vtk"})
    for (const auto& entry : std::filesystem::directory_iterator(folder))
      EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST(Pvd, FileNamesAreEscaped) {
  const std::string doc = pvd_document({{1.0, "a&b<\"c\".vtp"}});
  EXPECT_NE(doc.find("file=\"a&amp;b&lt;&quot;c&quot;.vtp\""), std::string::npos) << doc;
  EXPECT_NO_THROW(testing::parse_xml(doc));
}

}  // namespace
}  // namespace nodus::output
