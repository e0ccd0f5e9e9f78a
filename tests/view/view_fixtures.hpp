#pragma once
// Runs for the tests of `nodus view`'s page, made up here (not computed by nodus): fibres laid as a helix
// that twists from state to state, with node measures of known values and, on request, contact elements
// between neighbouring fibres, a tool beam and a branch.

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "nodus/output/result_data.hpp"

namespace nodus::test {

struct HelixRunSpec {
  int fibres = 3;
  int elements = 10;      // per fibre: 2 elements + 1 nodes
  int states = 6;         // of the main run, step 0 included
  bool contact = false;   // contact elements between neighbouring fibres, and a tool beam
  int branch_states = 0;  // a branch "release" with these states, when > 0
  double length = 4.0;    // [mm]
  double radius = 0.1;    // [mm]
};

inline std::array<double, 3> normalised(std::array<double, 3> v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / n, v[1] / n, v[2] / n};
}

/// One state: fibre f's centreline at s in [0, length] is the helix (a cos(theta_f + kappa s), a sin(...), s)
/// with twist rate `kappa` [1/mm]; g1 points away from the axis, normal to the tangent, g2 = t x g1.
inline output::ResultState helix_state(const output::ResultRun& run, const HelixRunSpec& spec, int step,
                                       double time, const std::string& stage, double kappa, double pull) {
  output::ResultState st;
  st.step = step;
  st.load_time = time;
  st.stage = stage;
  const double pi = std::acos(-1.0);
  const double a = spec.fibres > 1 ? spec.radius / std::sin(pi / spec.fibres) : 0.0;
  std::vector<double> e33, k1, k2;
  for (const output::ResultBeam& b : run.beams) {
    const int f = static_cast<int>(&b - run.beams.data());
    for (int i = 0; i < b.node_count; ++i) {
      const double s = spec.length * i / (b.node_count - 1);
      // A tool: a bar across the middle of the bundle, above it, pressing down as the fibres are pulled.
      if (b.tool) {
        const double x = (static_cast<double>(i) / (b.node_count - 1) - 0.5) * spec.length / 2;
        st.centre.push_back({x, a + spec.radius + b.radius + spec.radius * (1 - 50 * pull), spec.length / 2});
        st.g1.push_back({0, 1, 0});
        st.g2.push_back({0, 0, 1});
      } else {
        const double theta = 2 * pi * f / spec.fibres + kappa * s;
        const double z = s * (1 + pull);
        st.centre.push_back({a * std::cos(theta), a * std::sin(theta), z});
        const auto t = normalised({-a * kappa * std::sin(theta), a * kappa * std::cos(theta), 1 + pull});
        std::array<double, 3> r{std::cos(theta), std::sin(theta), 0.0};
        const double rt = r[0] * t[0] + r[1] * t[1] + r[2] * t[2];
        const auto g1 = normalised({r[0] - rt * t[0], r[1] - rt * t[1], r[2] - rt * t[2]});
        st.g1.push_back(g1);
        st.g2.push_back(
            {t[1] * g1[2] - t[2] * g1[1], t[2] * g1[0] - t[0] * g1[2], t[0] * g1[1] - t[1] * g1[0]});
      }
      e33.push_back(b.tool ? 0.0 : pull * (1 + pull / 2) + 1e-4 * std::sin(3 * s + f));
      k1.push_back(b.tool ? 0.0 : -a * kappa * kappa / (1 + a * a * kappa * kappa));
      k2.push_back(b.tool ? 0.0 : 0.05 * std::sin(2 * s) * kappa);
    }
  }
  st.node_fields["e33"] = e33;
  st.node_fields["k1"] = k1;
  st.node_fields["k2"] = k2;
  if (spec.contact && kappa != 0.0) {
    // Contact elements between fibres f and f + 1 at every second node, pressing harder as the twist grows.
    output::ResultContacts& c = st.contacts;
    const int fibres = spec.fibres;
    for (int f = 0; f < fibres; ++f) {
      const int g = (f + 1) % fibres;
      const output::ResultBeam& bi = run.beams[f];
      for (int i = 1; i + 1 < bi.node_count; i += 2) {
        const int ni = bi.first_node + i, nj = run.beams[g].first_node + i;
        c.zone.push_back(f);
        c.beam_i.push_back(f);
        c.beam_j.push_back(g);
        // The particles on the two surfaces, facing each other across the gap.
        const auto n = normalised({st.centre[nj][0] - st.centre[ni][0], st.centre[nj][1] - st.centre[ni][1],
                                   st.centre[nj][2] - st.centre[ni][2]});
        std::array<double, 3> xi, xj;
        for (int d = 0; d < 3; ++d) {
          xi[d] = st.centre[ni][d] + spec.radius * n[d];
          xj[d] = st.centre[nj][d] - spec.radius * n[d];
        }
        c.x_i.push_back(xi);
        c.x_j.push_back(xj);
        c.normal.push_back(n);
        c.gap.push_back((xj[0] - xi[0]) * n[0] + (xj[1] - xi[1]) * n[1] + (xj[2] - xi[2]) * n[2]);
        const double rn = 0.02 * kappa * (1 + 0.5 * std::sin(0.7 * i + f));
        c.normal_force.push_back(rn);
        c.tangential_force.push_back(0.3 * rn * (i % 3 == 0 ? 1.0 : 0.5));
        c.state.push_back(i % 3 == 0 ? "slip" : i % 5 == 0 ? "open" : "stick");
      }
    }
  }
  return st;
}

/// A run of `spec`: main stages "twist" and "pull" (the twist grows to 3 rad/mm over the first half of the
/// states, then the fibres are pulled by up to 2 %), and the branch "release" from its last state.
inline output::ResultRun helix_run(const HelixRunSpec& spec) {
  output::ResultRun run;
  run.name = "main";
  int first = 0;
  for (int f = 0; f < spec.fibres; ++f) {
    run.beams.push_back(
        {"fibre" + std::to_string(f), spec.radius, 4000.0, first, 2 * spec.elements + 1, false});
    first += 2 * spec.elements + 1;
  }
  if (spec.contact) run.beams.push_back({"tool", 2 * spec.radius, 210000.0, first, 5, true});
  const int half = std::max(1, spec.states / 2);
  run.stages = {{"twist", 0.0, 1.0}, {"pull", 1.0, 2.0}};
  for (int k = 0; k < spec.states; ++k) {
    const bool twist = k <= half;
    const double kappa = 3.0 * std::min(1.0, static_cast<double>(k) / half);
    const double pull = twist ? 0.0 : 0.02 * (k - half) / std::max(1, spec.states - 1 - half);
    const double time = twist ? static_cast<double>(k) / half : 1.0 + pull / 0.02;
    run.states.push_back(helix_state(run, spec, k, time, twist ? "twist" : "pull", kappa, pull));
  }
  if (spec.branch_states > 0) {
    output::ResultRun branch;
    branch.name = "release";
    branch.beams = run.beams;
    branch.stages = {{"release", 2.0, 3.0}};
    for (int k = 1; k <= spec.branch_states; ++k) {
      const double f = static_cast<double>(k) / spec.branch_states;
      branch.states.push_back(helix_state(run, spec, spec.states - 1 + k, 2.0 + f, "release",
                                          3.0 * (1 - 0.8 * f), 0.02 * (1 - f)));
    }
    run.branches.push_back(branch);
  }
  return run;
}

}  // namespace nodus::test
