// final_nodes.csv: header, one row per node of every beam, values equal to the state's.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "nodus/output/csv.hpp"
#include "nodus/output/final_nodes_table.hpp"
#include "output_test_support.hpp"

namespace nodus::output {
namespace {

using testing::ScratchDir;

void expect_table_matches(const std::string& text, const model::Model& m, const Eigen::VectorXd& x) {
  const auto lines = testing::split(text, '\n');
  ASSERT_EQ(static_cast<int>(lines.size()), 1 + m.num_nodes());
  EXPECT_EQ(lines[0], "beam,node,s,x,y,z,g1x,g1y,g1z,g2x,g2y,g2z");
  std::size_t row = 1;
  for (const beam::Beam& b : m.beams()) {
    for (int i = 0; i < b.num_nodes(); ++i, ++row) {
      const auto fields = testing::split(lines[row], ',');
      ASSERT_EQ(fields.size(), 12u) << lines[row];
      EXPECT_EQ(fields[0], b.name());
      EXPECT_EQ(std::stoi(fields[1]), i);
      EXPECT_NEAR(std::stod(fields[2]), b.abscissa(i), 1e-11 * b.length());
      for (int k = 0; k < 9; ++k) {
        const double expected = x[9 * b.node(i) + k];
        EXPECT_NEAR(std::stod(fields[3 + static_cast<std::size_t>(k)]), expected,
                    1e-11 * (1 + std::abs(expected)))
            << "beam " << b.name() << " node " << i << " value " << k;
      }
    }
  }
}

TEST(FinalNodes, ReferenceStateRowsMatchNodePlacement) {
  const model::Model m = testing::two_beam_model();
  ScratchDir dir;
  const auto path = dir.path() / "final_nodes.csv";
  write_final_nodes(path, m, m.reference());
  const std::string text = testing::read_text(path);
  expect_table_matches(text, m, m.reference());
  // Spot check: the last node of beam b sits at (1, 2, 3 + 4) with directors x and z x x = y.
  const auto lines = testing::split(text, '\n');
  EXPECT_EQ(lines.back(), "b,2,4,1,2,7,1,0,0,0,1,0");
}

TEST(FinalNodes, DeformedStateValuesAreWritten) {
  const model::Model m = testing::two_beam_model();
  const Eigen::VectorXd x = testing::deformed_state(m);
  expect_table_matches(final_nodes_csv(m, x), m, x);
}

TEST(FinalNodes, RejectsStateOfWrongSize) {
  const model::Model m = testing::two_beam_model();
  EXPECT_THROW(final_nodes_csv(m, Eigen::VectorXd::Zero(m.num_dofs() - 9)), std::invalid_argument);
}

TEST(Csv, FieldsAreQuotedOnlyWhenNeeded) {
  EXPECT_EQ(csv_field("clamp_left"), "clamp_left");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
}

}  // namespace
}  // namespace nodus::output
