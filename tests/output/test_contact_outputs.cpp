// Contact outputs: the VTK picture of a contact geometry (intermediate geometries and particle pairs), its
// .pvd collection, and the tables contact_final.csv and zones_final.csv, all for hand-built geometries and
// contact states.

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "nodus/output/contact_table.hpp"
#include "nodus/output/contact_vtk.hpp"
#include "nodus/output/vtk_series.hpp"
#include "output_test_support.hpp"

namespace nodus::output {
namespace {

using contact::Vec3;
using testing::ScratchDir;

/// Two zones and five contact elements: zone 0 between beams 0 and 1 (elements 0-2), zone 1 a self-contact
/// of beam 1 with antiparallel parts (elements 3-4). Positions and normals differ from element to element;
/// the gap is <x_j - x_i, n>, negative (overlap) for elements 1 and 4.
contact::ContactGeometry two_zone_geometry() {
  contact::ContactGeometry g;
  g.zones.push_back({0, 1, 1.5, 4.5, 0.5, 2.5, 0, 3});
  g.zones.push_back({1, 1, 3.0, 3.75, 1.25, 0.5, 3, 2});
  const double gaps[5] = {0.125, -0.0625, 0.25, 0.5, -0.03125};
  for (int e = 0; e < 5; ++e) {
    contact::ContactElement c;
    c.zone = e < 3 ? 0 : 1;
    const contact::ProximityZone& z = g.zones[static_cast<std::size_t>(c.zone)];
    const int k = e < 3 ? e : e - 3;
    const int n = z.num_elements;
    c.zeta = (k + 0.5) / n;
    c.particle_i.beam = z.beam_i;
    c.particle_j.beam = z.beam_j;
    c.particle_i.abscissa = z.a + c.zeta * (z.b - z.a);
    c.particle_j.abscissa = z.c + c.zeta * (z.d - z.c);
    c.particle_i.transverse = Eigen::Vector2d(0.3 + 0.01 * e, -0.4);
    c.particle_j.transverse = Eigen::Vector2d(-0.15, 0.2 - 0.01 * e);
    const double angle = 0.3 * e;
    c.normal = Vec3(std::cos(angle) * 0.6, std::sin(angle) * 0.6, 0.8);
    c.position_i = Vec3(1.0 + e, 2.0 - 0.5 * e, 0.25 * e * e);
    c.position_j = c.position_i + gaps[e] * c.normal + Vec3(-c.normal.y(), c.normal.x(), 0.0) * 0.01;
    c.gap = (c.position_j - c.position_i).dot(c.normal);
    c.intermediate = 0.5 * (c.position_i + c.position_j);
    g.elements.push_back(c);
  }
  return g;
}

/// One contact state per element of two_zone_geometry(): element 0 open, 1 sticking, 2 sliding, 3 closed
/// without friction force (stick), 4 sliding. The friction forces lie in the plane normal to the element's
/// normal, as the friction law makes them.
std::vector<simulation::ContactState> five_states(const contact::ContactGeometry& g) {
  const double reactions[5] = {0.0, 2.5, 0.75, 1e-3, 4.0};
  const bool slip[5] = {false, false, true, false, true};
  const double friction[5] = {0.0, 0.125, 0.225, 0.0, 1.2};  // |T| [N]
  std::vector<simulation::ContactState> states(5);
  for (std::size_t e = 0; e < 5; ++e) {
    const Vec3& n = g.elements[e].normal;
    const Vec3 t = n.cross(Vec3(1.0, 0.5 * static_cast<double>(e), -0.25)).normalized();
    states[e].gap = g.elements[e].gap;
    states[e].normal_reaction = reactions[e];
    states[e].tangential = friction[e] * t;
    states[e].slip = slip[e];
  }
  return states;
}

const std::vector<std::string> kBeamNames{"a", "b"};

void expect_close(double read, double expected, const std::string& what) {
  EXPECT_NEAR(read, expected, 1e-9 * (1 + std::abs(expected))) << what;
}

std::unique_ptr<testing::XmlElement> contact_document(const contact::ContactGeometry& g,
                                                      std::optional<double> time,
                                                      VtkEncoding encoding = VtkEncoding::binary) {
  std::ostringstream out;
  write_contact_vtp(out, g, time, nullptr, encoding);
  return testing::parse_vtk(out.str());
}

/// The tests that read a document back, in either encoding.
class ContactVtpIn : public ::testing::TestWithParam<VtkEncoding> {};

INSTANTIATE_TEST_SUITE_P(Encodings, ContactVtpIn, ::testing::Values(VtkEncoding::binary, VtkEncoding::ascii),
                         [](const auto& info) {
                           return info.param == VtkEncoding::binary ? "binary" : "ascii";
                         });

TEST_P(ContactVtpIn, PolylinesPerZoneAndSegmentsPerElement) {
  const contact::ContactGeometry g = two_zone_geometry();
  const auto root = contact_document(g, 0.75, GetParam());
  ASSERT_EQ(root->name, "VTKFile");
  EXPECT_EQ(root->attribute("type"), "PolyData");
  const testing::XmlElement& poly = root->one("PolyData");
  EXPECT_DOUBLE_EQ(testing::numbers(poly.one("FieldData").data_array("TimeValue").text).at(0), 0.75);
  const testing::XmlElement& piece = poly.one("Piece");
  EXPECT_EQ(piece.attribute("NumberOfPoints"), "15");  // 5 intermediate points + 5 particle pairs
  EXPECT_EQ(piece.attribute("NumberOfLines"), "7");    // 2 zone polylines + 5 element segments
  EXPECT_EQ(piece.attribute("NumberOfVerts"), "0");
  EXPECT_EQ(piece.attribute("NumberOfPolys"), "0");
  EXPECT_EQ(piece.attribute("NumberOfStrips"), "0");
  EXPECT_TRUE(piece.all("PointData").empty());

  const auto points = testing::numbers(piece.one("Points").one("DataArray").text);
  ASSERT_EQ(points.size(), 45u);
  auto point = [&](double index) {
    const auto p = static_cast<std::size_t>(3 * index);
    return Vec3(points.at(p), points.at(p + 1), points.at(p + 2));
  };

  const testing::XmlElement& lines = piece.one("Lines");
  const auto connectivity = testing::numbers(lines.data_array("connectivity").text);
  const auto offsets = testing::numbers(lines.data_array("offsets").text);
  EXPECT_EQ(connectivity, (std::vector<double>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14}));
  EXPECT_EQ(offsets, (std::vector<double>{3, 5, 7, 9, 11, 13, 15}));
  // The polylines run through the intermediate points of their zone's elements, in order.
  for (int e = 0; e < 5; ++e)
    EXPECT_LT((point(connectivity[static_cast<std::size_t>(e)]) -
               g.elements[static_cast<std::size_t>(e)].intermediate)
                  .norm(),
              1e-10)
        << e;
  // Segment e goes from position_i to position_j of element e.
  for (int e = 0; e < 5; ++e) {
    const std::size_t end = static_cast<std::size_t>(offsets[static_cast<std::size_t>(2 + e)]);
    ASSERT_EQ(end - static_cast<std::size_t>(offsets[static_cast<std::size_t>(1 + e)]), 2u);
    const contact::ContactElement& c = g.elements[static_cast<std::size_t>(e)];
    EXPECT_LT((point(connectivity[end - 2]) - c.position_i).norm(), 1e-10) << e;
    EXPECT_LT((point(connectivity[end - 1]) - c.position_j).norm(), 1e-10) << e;
  }

  const testing::XmlElement& data = piece.one("CellData");
  EXPECT_EQ(data.all("DataArray").size(), 6u);
  for (const char* name : {"kind", "zone", "beam_i", "beam_j"})
    EXPECT_EQ(data.data_array(name).attribute("type"), "Int32") << name;
  EXPECT_EQ(data.data_array("gap").attribute("type"), "Float64");
  EXPECT_EQ(data.data_array("normal").attribute("type"), "Float64");
  EXPECT_EQ(data.data_array("normal").attribute("NumberOfComponents"), "3");
  EXPECT_EQ(testing::numbers(data.data_array("kind").text), (std::vector<double>{0, 0, 1, 1, 1, 1, 1}));
  EXPECT_EQ(testing::numbers(data.data_array("zone").text), (std::vector<double>{0, 1, 0, 0, 0, 1, 1}));
  EXPECT_EQ(testing::numbers(data.data_array("beam_i").text), (std::vector<double>{0, 1, 0, 0, 0, 1, 1}));
  EXPECT_EQ(testing::numbers(data.data_array("beam_j").text), (std::vector<double>{1, 1, 1, 1, 1, 1, 1}));

  const auto gap = testing::numbers(data.data_array("gap").text);
  ASSERT_EQ(gap.size(), 7u);
  expect_close(gap[0], g.elements[1].gap, "smallest gap of zone 0");
  expect_close(gap[1], g.elements[4].gap, "smallest gap of zone 1");
  for (std::size_t e = 0; e < 5; ++e) expect_close(gap[2 + e], g.elements[e].gap, "gap " + std::to_string(e));

  const auto normal = testing::numbers(data.data_array("normal").text);
  ASSERT_EQ(normal.size(), 21u);
  for (std::size_t k = 0; k < 6; ++k) EXPECT_EQ(normal[k], 0.0);
  for (std::size_t e = 0; e < 5; ++e)
    for (int k = 0; k < 3; ++k)
      expect_close(normal[6 + 3 * e + static_cast<std::size_t>(k)], g.elements[e].normal[k], "normal");
}

TEST(ContactVtp, ContactForcesOnTheSegmentsZerosOnThePolylines) {
  const contact::ContactGeometry g = two_zone_geometry();
  const std::vector<simulation::ContactState> states = five_states(g);
  std::ostringstream out;
  write_contact_vtp(out, g, 0.5, &states);
  const auto root = testing::parse_vtk(out.str());
  const testing::XmlElement& data = root->one("PolyData").one("Piece").one("CellData");
  EXPECT_EQ(data.all("DataArray").size(), 10u);
  EXPECT_EQ(data.data_array("normal_force").attribute("type"), "Float64");
  EXPECT_EQ(data.data_array("normal_force").attributes.count("NumberOfComponents"), 0u);  // a scalar
  for (const char* name : {"force", "tangential_force"}) {
    EXPECT_EQ(data.data_array(name).attribute("type"), "Float64") << name;
    EXPECT_EQ(data.data_array(name).attribute("NumberOfComponents"), "3") << name;
  }
  EXPECT_EQ(data.data_array("state").attribute("type"), "Int32");
  // Cells: 2 zone polylines (zeros), then the 5 element segments.
  EXPECT_EQ(testing::numbers(data.data_array("state").text), (std::vector<double>{0, 0, 0, 1, 2, 1, 2}));
  const auto normal_force = testing::numbers(data.data_array("normal_force").text);
  const auto force = testing::numbers(data.data_array("force").text);
  const auto tangential = testing::numbers(data.data_array("tangential_force").text);
  ASSERT_EQ(normal_force.size(), 7u);
  ASSERT_EQ(force.size(), 21u);
  ASSERT_EQ(tangential.size(), 21u);
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(force[k], 0.0);
    EXPECT_EQ(tangential[k], 0.0);
  }
  EXPECT_EQ(normal_force[0], 0.0);
  EXPECT_EQ(normal_force[1], 0.0);
  for (std::size_t e = 0; e < 5; ++e) {
    const simulation::ContactState& s = states[e];
    const Vec3& n = g.elements[e].normal;
    expect_close(normal_force[2 + e], s.normal_reaction, "normal_force " + std::to_string(e));
    for (int k = 0; k < 3; ++k) {
      const std::size_t i = 6 + 3 * e + static_cast<std::size_t>(k);
      // The force on beam J: R_N along the normal from I to J, plus the friction force on J.
      expect_close(force[i], s.normal_reaction * n[k] + s.tangential[k], "force " + std::to_string(e));
      expect_close(tangential[i], s.tangential[k], "tangential_force " + std::to_string(e));
    }
  }
  // The friction force is tangential: the normal component of `force` is R_N.
  for (std::size_t e = 0; e < 5; ++e) {
    const Vec3 f(force[6 + 3 * e], force[7 + 3 * e], force[8 + 3 * e]);
    expect_close(f.dot(g.elements[e].normal), states[e].normal_reaction, "<force, n>");
  }
}

TEST(ContactVtp, RejectsStatesThatDoNotMatchTheElements) {
  const contact::ContactGeometry g = two_zone_geometry();
  std::vector<simulation::ContactState> states = five_states(g);
  states.pop_back();
  std::ostringstream out;
  EXPECT_THROW(write_contact_vtp(out, g, std::nullopt, &states), std::invalid_argument);
  // An empty geometry takes an empty set of states and gives empty force arrays.
  const std::vector<simulation::ContactState> none;
  std::ostringstream empty;
  write_contact_vtp(empty, contact::ContactGeometry{}, 1.0, &none);
  const auto root = testing::parse_vtk(empty.str());
  const testing::XmlElement& data = root->one("PolyData").one("Piece").one("CellData");
  for (const char* name : {"normal_force", "force", "tangential_force", "state"})
    EXPECT_TRUE(testing::numbers(data.data_array(name).text).empty()) << name;
}

TEST_P(ContactVtpIn, EmptyGeometryGivesAValidEmptyDocument) {
  const auto root = contact_document(contact::ContactGeometry{}, 2.0, GetParam());
  const testing::XmlElement& poly = root->one("PolyData");
  EXPECT_DOUBLE_EQ(testing::numbers(poly.one("FieldData").data_array("TimeValue").text).at(0), 2.0);
  const testing::XmlElement& piece = poly.one("Piece");
  EXPECT_EQ(piece.attribute("NumberOfPoints"), "0");
  EXPECT_EQ(piece.attribute("NumberOfLines"), "0");
  EXPECT_TRUE(testing::numbers(piece.one("Points").one("DataArray").text).empty());
  EXPECT_TRUE(testing::numbers(piece.one("Lines").data_array("connectivity").text).empty());
  EXPECT_TRUE(testing::numbers(piece.one("Lines").data_array("offsets").text).empty());
  const testing::XmlElement& data = piece.one("CellData");
  for (const char* name : {"kind", "zone", "beam_i", "beam_j", "gap", "normal"})
    EXPECT_TRUE(testing::numbers(data.data_array(name).text).empty()) << name;

  // Without a time there is no field data.
  EXPECT_TRUE(
      contact_document(contact::ContactGeometry{}, std::nullopt)->one("PolyData").all("FieldData").empty());
}

TEST(ContactVtp, ZoneWithoutElementsHasNoPolyline) {
  contact::ContactGeometry g = two_zone_geometry();
  g.zones.push_back({0, 1, 6.0, 7.0, 3.0, 3.5, 5, 0});
  const auto root = contact_document(g, std::nullopt);
  const testing::XmlElement& piece = root->one("PolyData").one("Piece");
  EXPECT_EQ(piece.attribute("NumberOfLines"), "7");
  EXPECT_EQ(testing::numbers(piece.one("CellData").data_array("zone").text),
            (std::vector<double>{0, 1, 0, 0, 0, 1, 1}));
}

TEST(ContactVtp, RejectsInconsistentGeometry) {
  std::ostringstream out;
  contact::ContactGeometry g = two_zone_geometry();
  g.elements[2].zone = 2;
  EXPECT_THROW(write_contact_vtp(out, g), std::invalid_argument);
  g = two_zone_geometry();
  g.zones[1].num_elements = 3;  // runs past the last element
  EXPECT_THROW(write_contact_vtp(out, g), std::invalid_argument);
}

TEST(ContactPvd, SeriesListsContactFiles) {
  const model::Model m = testing::two_beam_model();
  const contact::ContactGeometry g = two_zone_geometry();
  ScratchDir dir;
  // Contact files of an earlier run are removed by begin(); other files are kept.
  std::filesystem::create_directories(dir.path() / "vtk");
  write_contact_vtp(dir.path() / "vtk" / "contact_000099.vtp", g);
  write_contact_vtp(dir.path() / "vtk" / "contact_mine.vtp", g);

  VtkSeries series(dir.path(), 5);
  series.begin(true);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "vtk" / "contact_000099.vtp"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "vtk" / "contact_mine.vtp"));
  EXPECT_TRUE(
      testing::parse_xml(testing::read_text(series.contact_pvd_path()))->one("Collection").children.empty());

  series.write(0, 0.0, m, m.reference(), &g);
  series.write(4, 0.5, m, testing::deformed_state(m), &g);
  const contact::ContactGeometry empty;
  series.write(9, 1.25, m, testing::deformed_state(m), &empty);
  series.write(9, 1.25, m, testing::deformed_state(m), &empty);  // again: replaces, no second entry
  EXPECT_EQ(series.contact_entries().size(), 3u);

  const std::vector<std::pair<std::string, double>> expected{
      {"vtk/contact_000000.vtp", 0.0}, {"vtk/contact_000004.vtp", 0.5}, {"vtk/contact_000009.vtp", 1.25}};
  const auto root = testing::parse_xml(testing::read_text(dir.path() / "contact.pvd"));
  EXPECT_EQ(root->attribute("type"), "Collection");
  const auto sets = root->one("Collection").all("DataSet");
  ASSERT_EQ(sets.size(), expected.size());
  for (std::size_t i = 0; i < sets.size(); ++i) {
    EXPECT_EQ(sets[i]->attribute("file"), expected[i].first);
    EXPECT_DOUBLE_EQ(std::stod(sets[i]->attribute("timestep")), expected[i].second);
    const auto file = testing::parse_vtk(testing::read_text(dir.path() / expected[i].first));
    const testing::XmlElement& poly = file->one("PolyData");
    EXPECT_DOUBLE_EQ(testing::numbers(poly.one("FieldData").data_array("TimeValue").text).at(0),
                     expected[i].second);
    EXPECT_EQ(poly.one("Piece").attribute("NumberOfLines"), i < 2 ? "7" : "0");
  }
  // The beam pictures are written for the same steps.
  const auto beam_root = testing::parse_xml(testing::read_text(series.pvd_path()));
  const auto beams = beam_root->one("Collection").all("DataSet");
  ASSERT_EQ(beams.size(), 3u);
  EXPECT_EQ(beams[1]->attribute("file"), "vtk/step_000004.vtp");

  // A later run without contact removes the contact files and collection.
  VtkSeries plain(dir.path(), 5);
  plain.begin(false);
  plain.write(0, 0.0, m, m.reference());
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "contact.pvd"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "vtk" / "contact_000000.vtp"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "vtk" / "step_000000.vtp"));
  EXPECT_TRUE(plain.contact_entries().empty());
  for (const auto& folder : {dir.path(), dir.path() / "vtk"})
    for (const auto& entry : std::filesystem::directory_iterator(folder))
      EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST(ContactCsv, ElementRowsReadBackEqualTheInputs) {
  const contact::ContactGeometry g = two_zone_geometry();
  ScratchDir dir;
  write_contact_final(dir.path() / "contact_final.csv", g, kBeamNames);
  const std::string text = testing::read_text(dir.path() / "contact_final.csv");
  EXPECT_EQ(text, contact_final_csv(g, kBeamNames));
  const auto lines = testing::split(text, '\n');
  ASSERT_EQ(lines.size(), 6u);
  EXPECT_EQ(
      lines[0],
      "zone,beam_i,beam_j,zeta,abscissa_i,abscissa_j,xi1_i,xi2_i,xi1_j,xi2_j,x_i,y_i,z_i,x_j,y_j,z_j,nx,ny,"
      "nz,gap");
  for (std::size_t e = 0; e < 5; ++e) {
    const contact::ContactElement& c = g.elements[e];
    const contact::ProximityZone& z = g.zones[static_cast<std::size_t>(c.zone)];
    const auto f = testing::split(lines[1 + e], ',');
    ASSERT_EQ(f.size(), 20u) << lines[1 + e];
    EXPECT_EQ(std::stoi(f[0]), c.zone);
    EXPECT_EQ(f[1], kBeamNames[static_cast<std::size_t>(z.beam_i)]);
    EXPECT_EQ(f[2], kBeamNames[static_cast<std::size_t>(z.beam_j)]);
    const double expected[17] = {c.zeta,
                                 c.particle_i.abscissa,
                                 c.particle_j.abscissa,
                                 c.particle_i.transverse.x(),
                                 c.particle_i.transverse.y(),
                                 c.particle_j.transverse.x(),
                                 c.particle_j.transverse.y(),
                                 c.position_i.x(),
                                 c.position_i.y(),
                                 c.position_i.z(),
                                 c.position_j.x(),
                                 c.position_j.y(),
                                 c.position_j.z(),
                                 c.normal.x(),
                                 c.normal.y(),
                                 c.normal.z(),
                                 c.gap};
    for (std::size_t k = 0; k < 17; ++k)
      expect_close(std::stod(f[3 + k]), expected[k],
                   "element " + std::to_string(e) + " column " + std::to_string(3 + k));
  }
  // The self-contact rows name the same beam twice.
  EXPECT_EQ(lines[4].substr(0, 6), "1,b,b,");
}

TEST(ContactCsv, ForceColumnsFollowTheGeometryColumns) {
  const contact::ContactGeometry g = two_zone_geometry();
  const std::vector<simulation::ContactState> states = five_states(g);
  ScratchDir dir;
  write_contact_final(dir.path() / "contact_final.csv", g, kBeamNames, &states);
  const auto lines = testing::split(testing::read_text(dir.path() / "contact_final.csv"), '\n');
  ASSERT_EQ(lines.size(), 6u);
  EXPECT_EQ(
      lines[0],
      "zone,beam_i,beam_j,zeta,abscissa_i,abscissa_j,xi1_i,xi2_i,xi1_j,xi2_j,x_i,y_i,z_i,x_j,y_j,z_j,nx,ny,"
      "nz,gap,normal_force,tangential_force,tx,ty,tz,state");
  const char* expected_state[5] = {"open", "stick", "slip", "stick", "slip"};
  for (std::size_t e = 0; e < 5; ++e) {
    const contact::ContactElement& c = g.elements[e];
    const simulation::ContactState& s = states[e];
    const auto f = testing::split(lines[1 + e], ',');
    ASSERT_EQ(f.size(), 26u) << lines[1 + e];
    // The geometry columns are those of the table without forces.
    EXPECT_EQ(std::stoi(f[0]), c.zone);
    expect_close(std::stod(f[3]), c.zeta, "zeta");
    expect_close(std::stod(f[16]), c.normal.x(), "nx");
    expect_close(std::stod(f[19]), c.gap, "gap");
    expect_close(std::stod(f[20]), s.normal_reaction, "normal_force " + std::to_string(e));
    const double magnitude =
        std::sqrt(s.tangential.x() * s.tangential.x() + s.tangential.y() * s.tangential.y() +
                  s.tangential.z() * s.tangential.z());
    expect_close(std::stod(f[21]), magnitude, "tangential_force " + std::to_string(e));
    for (int k = 0; k < 3; ++k)
      expect_close(std::stod(f[22 + static_cast<std::size_t>(k)]), s.tangential[k], "t " + std::to_string(e));
    EXPECT_EQ(f[25], expected_state[e]) << e;
  }
  EXPECT_EQ(status_name(contact_status(states[0])), "open");
  EXPECT_EQ(static_cast<int>(contact_status(states[1])), 1);
  EXPECT_EQ(static_cast<int>(contact_status(states[2])), 2);

  // Without states the table keeps its 20 columns; with states that do not match the elements it is refused.
  EXPECT_EQ(testing::split(testing::split(contact_final_csv(g, kBeamNames), '\n')[1], ',').size(), 20u);
  const std::vector<simulation::ContactState> fewer(states.begin(), states.begin() + 4);
  EXPECT_THROW(contact_final_csv(g, kBeamNames, &fewer), std::invalid_argument);
  EXPECT_EQ(contact_csv_header(false) + ",normal_force,tangential_force,tx,ty,tz,state",
            contact_csv_header(true));
}

TEST(ContactCsv, ZoneRowsReadBackEqualTheInputs) {
  contact::ContactGeometry g = two_zone_geometry();
  g.zones.push_back({0, 1, 6.0, 7.0, 3.0, 3.5, 5, 0});  // no elements: empty min_gap
  ScratchDir dir;
  write_zones_final(dir.path() / "zones_final.csv", g, kBeamNames);
  const std::string text = testing::read_text(dir.path() / "zones_final.csv");
  EXPECT_EQ(text, zones_final_csv(g, kBeamNames));
  const auto lines = testing::split(text, '\n');
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "zone,beam_i,beam_j,a,b,c,d,contact_elements,min_gap");
  const std::vector<std::vector<std::string>> expected{{"0", "a", "b", "1.5", "4.5", "0.5", "2.5", "3"},
                                                       {"1", "b", "b", "3", "3.75", "1.25", "0.5", "2"}};
  const std::size_t smallest[2] = {1, 4};  // the element of smallest gap in each zone
  for (std::size_t z = 0; z < 2; ++z) {
    const auto f = testing::split(lines[1 + z], ',');
    ASSERT_EQ(f.size(), 9u) << lines[1 + z];
    EXPECT_EQ(std::vector<std::string>(f.begin(), f.begin() + 8), expected[z]);
    expect_close(std::stod(f[8]), g.elements[smallest[z]].gap, "min_gap of zone " + std::to_string(z));
  }
  EXPECT_EQ(lines[3], "2,a,b,6,7,3,3.5,0,");
}

TEST(ContactCsv, NamesAreQuotedAndIndicesChecked) {
  const contact::ContactGeometry g = two_zone_geometry();
  EXPECT_NE(zones_final_csv(g, {"a", "left, outer"}).find("0,a,\"left, outer\",1.5"), std::string::npos);
  EXPECT_THROW(contact_final_csv(g, {"a"}), std::invalid_argument);
  EXPECT_THROW(zones_final_csv(g, {"a"}), std::invalid_argument);
  contact::ContactGeometry bad = g;
  bad.elements[0].zone = -1;
  EXPECT_THROW(contact_final_csv(bad, kBeamNames), std::invalid_argument);
  // An empty geometry gives the header only.
  EXPECT_EQ(testing::split(contact_final_csv({}, kBeamNames), '\n').size(), 1u);
  EXPECT_EQ(zones_final_csv({}, kBeamNames), "zone,beam_i,beam_j,a,b,c,d,contact_elements,min_gap\n");
}

TEST(ContactCsv, BeamNamesOfAModel) {
  EXPECT_EQ(beam_names(testing::two_beam_model()), kBeamNames);
}

}  // namespace
}  // namespace nodus::output
