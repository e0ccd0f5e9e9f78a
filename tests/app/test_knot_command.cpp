// `nodus knot NODES.csv`: the knot type and smallest self-distance of a beam read from a nodal table. The
// references are curves of known type: the trefoil T(2, 3) cut open at its outermost point (Alexander
// polynomial 1 - t + t^2), a straight line (the unknot), and a hairpin whose legs lie 0.5 mm apart.

#include <gtest/gtest.h>

#include "cli_test_support.hpp"

#include <sys/wait.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>
#include <string>
#include <tuple>

namespace {

namespace fs = std::filesystem;

using nodus::testing::run_nodus;
using nodus::testing::scratch;

struct Point {
  double x, y, z;
};

/// A nodal table of `n` nodes of `curve(u)`, u in [0, 1], s the chord length along it (beam `name`).
std::string table(const std::string& name, int n, const std::function<Point(double)>& curve) {
  std::ostringstream out;
  out << "beam,node,s,x,y,z,g1x,g1y,g1z,g2x,g2y,g2z\n";
  double s = 0.0;
  Point previous = curve(0.0);
  for (int i = 0; i < n; ++i) {
    const Point p = curve(static_cast<double>(i) / (n - 1));
    s += std::hypot(p.x - previous.x, p.y - previous.y, p.z - previous.z);
    previous = p;
    char row[256];
    std::snprintf(row, sizeof row, "%s,%d,%.12g,%.12g,%.12g,%.12g,0,1,0,0,0,1\n", name.c_str(), i, s, p.x,
                  p.y, p.z);
    out << row;
  }
  return out.str();
}

/// Runs `nodus knot` on `text` written to a file; stdout and the exit status.
std::pair<int, std::string> knot(const std::string& text, const std::string& options = "") {
  const fs::path nodes = scratch() / "knot_nodes.csv", out = scratch() / "knot_out.txt";
  std::ofstream(nodes) << text;
  const int status = std::system(
      (std::string(NODUS_BINARY) + " knot " + nodes.string() + " " + options + " > " + out.string() + " 2>&1")
          .c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, nodus::testing::read_file(out)};
}

const double kPi = std::numbers::pi;

TEST(KnotCommand, FindsTheTrefoil) {
  // T(2, 3) from t = delta to 2 pi - delta: cut open at t = 0, where x = 3 is largest.
  const auto trefoil = [](double u) {
    const double t = 0.01 + (2 * kPi - 0.02) * u, r = 2 + std::cos(3 * t);
    return Point{r * std::cos(2 * t), r * std::sin(2 * t), -std::sin(3 * t)};
  };
  const auto [status, text] = knot(table("rod", 400, trefoil));
  EXPECT_EQ(status, 0) << text;
  EXPECT_NE(text.find("Alexander polynomial 1 - t + t^2 (trefoil; determinant 3;"), std::string::npos)
      << text;
  EXPECT_NE(text.find("beam rod, 400 nodes"), std::string::npos) << text;
}

TEST(KnotCommand, FindsTheUnknotAndTheGapOfAHairpin) {
  // Two straight legs 0.5 mm apart joined by a half circle of radius 0.25 mm; legs 5 mm long.
  const double leg = 5.0, radius = 0.25, half = kPi * radius, total = 2 * leg + half;
  const auto hairpin = [=](double u) {
    const double l = u * total;
    if (l < leg) return Point{l, radius, 0};
    if (l < leg + half) {
      const double a = (l - leg) / radius;
      return Point{leg + radius * std::sin(a), radius * std::cos(a), 0};
    }
    return Point{leg - (l - leg - half), -radius, 0};
  };
  // The first beam of the table is read unless --beam names another.
  const std::string two = table("pin", 801, hairpin) +
                          table("line", 3, [](double u) {
                            return Point{u, 0, 0};
                          }).substr(std::string("beam,node,s,x,y,z,g1x,g1y,g1z,g2x,g2y,g2z\n").size());
  const auto [status, text] = knot(two, "--separation 2");
  EXPECT_EQ(status, 0) << text;
  EXPECT_NE(text.find("Alexander polynomial 1 (unknot;"), std::string::npos) << text;
  EXPECT_NE(text.find("smallest distance 0.500000 mm"), std::string::npos) << text;
  const auto [status_line, line] = knot(two, "--beam line");
  EXPECT_EQ(status_line, 0) << line;
  EXPECT_NE(line.find("beam line, 3 nodes"), std::string::npos) << line;
}

TEST(KnotCommand, ReportsEachFibreOfAYarnTheirMeanAndTheirDistances) {
  // Three straight fibres y.r1.f1, y.r2.f1, y.r3.f1 along x at (y, z) = (0, 0), (0.5, 0), (0, 0.3), and a
  // beam of another name: the fibres and their mean are unknots, the fibres 0.5, 0.3 and sqrt(0.34) apart.
  const std::string header = "beam,node,s,x,y,z,g1x,g1y,g1z,g2x,g2y,g2z\n";
  const auto line = [](double y, double z) { return [=](double u) { return Point{4 * u, y, z}; }; };
  std::string text = table("y.r1.f1", 9, line(0, 0));
  for (const auto& [name, y, z] :
       {std::tuple{"y.r2.f1", 0.5, 0.0}, {"y.r3.f1", 0.0, 0.3}, {"other", 2.0, 0.0}})
    text += table(name, 9, line(y, z)).substr(header.size());
  const auto [status, out] = knot(text, "--yarn y");
  EXPECT_EQ(status, 0) << out;
  for (const char* fibre : {"beam y.r1.f1, 9 nodes", "beam y.r2.f1, 9 nodes", "beam y.r3.f1, 9 nodes"})
    EXPECT_NE(out.find(fibre), std::string::npos) << out;
  EXPECT_EQ(out.find("beam other"), std::string::npos) << out;
  EXPECT_NE(out.find("mean centreline of the 3 beams: knot: Alexander polynomial 1 (unknot;"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("smallest distance 0.500000 mm between beams y.r1.f1 (s = "), std::string::npos) << out;
  EXPECT_NE(out.find("smallest distance 0.300000 mm between beams y.r1.f1 (s = "), std::string::npos) << out;
  char diagonal[64];
  std::snprintf(diagonal, sizeof diagonal, "smallest distance %.6f mm between beams y.r2.f1",
                std::sqrt(0.34));
  EXPECT_NE(out.find(diagonal), std::string::npos) << out;

  // The same beams named one by one.
  const auto [status_beams, beams] = knot(text, "--beam y.r1.f1 --beam other");
  EXPECT_EQ(status_beams, 0) << beams;
  EXPECT_NE(beams.find("smallest distance 2.000000 mm between beams y.r1.f1"), std::string::npos) << beams;

  // No such yarn; fibres of unequal numbers of nodes.
  const auto [status_none, none] = knot(text, "--yarn x");
  EXPECT_EQ(status_none, 2);
  EXPECT_NE(none.find("expected the fibres x.rK.fJ of yarn x in the table, got none"), std::string::npos)
      << none;
  const std::string uneven =
      table("y.r1.f1", 9, line(0, 0)) + table("y.r2.f1", 5, line(0.5, 0)).substr(header.size());
  const auto [status_uneven, message] = knot(uneven, "--yarn y");
  EXPECT_EQ(status_uneven, 2);
  EXPECT_NE(
      message.find("expected beams of equal numbers of nodes (the fibres of a yarn), got 9 and 5 nodes"),
      std::string::npos)
      << message;
}

TEST(KnotCommand, BadTablesGiveOneLineAndStatus2) {
  const auto [status, text] = knot("step,stage,time\n1,a,0.5\n");
  EXPECT_EQ(status, 2);
  EXPECT_NE(text.find("knot_nodes.csv:1: expected the header beam,node,s,x,y,z,..., got 'step,stage,time'"),
            std::string::npos)
      << text;
  const auto [status_number, number] = knot("beam,node,s,x,y,z\nrod,0,0,0,0,0\nrod,1,1,abc,0,0\n");
  EXPECT_EQ(status_number, 2);
  EXPECT_NE(number.find("knot_nodes.csv:3: expected a number in column x, got 'abc'"), std::string::npos)
      << number;
  const auto [status_beam, beam] = knot("beam,node,s,x,y,z\nrod,0,0,0,0,0\nrod,1,1,1,0,0\n", "--beam tool");
  EXPECT_EQ(status_beam, 2);
  EXPECT_NE(beam.find("expected at least two nodes of beam tool, got 0"), std::string::npos) << beam;
  EXPECT_EQ(std::count(beam.begin(), beam.end(), '\n'), 1) << beam;
}

}  // namespace
