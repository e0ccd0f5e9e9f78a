#include "nodus/beam/shape_functions.hpp"

#include <stdexcept>

namespace nodus::beam {
namespace {
constexpr std::array<GaussPoint, 1> kGauss1{{{0.0, 2.0}}};
constexpr std::array<GaussPoint, 2> kGauss2{{{-0.57735026918962576, 1.0}, {0.57735026918962576, 1.0}}};
constexpr std::array<GaussPoint, 3> kGauss3{
    {{-0.77459666924148338, 5.0 / 9.0}, {0.0, 8.0 / 9.0}, {0.77459666924148338, 5.0 / 9.0}}};
constexpr std::array<GaussPoint, 4> kGauss4{{{-0.86113631159405258, 0.34785484513745386},
                                             {-0.33998104358485626, 0.65214515486254614},
                                             {0.33998104358485626, 0.65214515486254614},
                                             {0.86113631159405258, 0.34785484513745386}}};
constexpr std::array<GaussPoint, 5> kGauss5{{{-0.90617984593866399, 0.23692688505618909},
                                             {-0.53846931010568309, 0.47862867049936647},
                                             {0.0, 0.56888888888888889},
                                             {0.53846931010568309, 0.47862867049936647},
                                             {0.90617984593866399, 0.23692688505618909}}};
}  // namespace

std::span<const GaussPoint> gauss_rule(int n) {
  switch (n) {
    case 1:
      return kGauss1;
    case 2:
      return kGauss2;
    case 3:
      return kGauss3;
    case 4:
      return kGauss4;
    case 5:
      return kGauss5;
    default:
      throw std::invalid_argument("gauss_rule: number of points must be in 1..5");
  }
}

}  // namespace nodus::beam
