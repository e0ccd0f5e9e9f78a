#pragma once
/// The expansion of a yarn (YarnSpec, docs/yarns.md) into the beams of its fibres and the rigid bodies at the
/// ends of its rovings: what the reader does with each item of `yarns`, and what a scenario built in code
/// calls (append_yarn) so that validate() accepts it.

#include <string>
#include <vector>

#include "nodus/scenario/scenario.hpp"

namespace nodus::scenario {

/// Most fibres of one yarn (rovings x fibres_per_roving): the layout tries 720 turns of the roving pattern,
/// each over all pairs of fibres of different rovings.
constexpr int kMaxYarnFibres = 1000;

/// "NAME.rK.fJ": fibre `fibre` (from 0) of roving `roving` (from 0), numbered from 1 in the name.
std::string yarn_beam_name(const std::string& yarn, int roving, int fibre);
/// "NAME.rK.start" or "NAME.rK.end", roving from 0.
std::string yarn_body_name(const std::string& yarn, int roving, bool at_end);

/// The fibres of `yarn` (direction unit), roving after roving: straight beams along `direction` from
/// start + u e1 + v e2, (u, v) the fibre's point of model::yarn_layout with spacing 2 R + gap(), e1 the
/// default director1 of `direction` (beams[].director1: auto), e2 = direction x e1; every fibre has
/// director1 = e1 and the yarn's material, radius, length, elements and bending_factor.
std::vector<BeamSpec> yarn_beams(const YarnSpec& yarn);

/// With yarn.bodies, two bodies per roving (its start body, then its end body) binding node 0 and node
/// 2 elements of each of its fibres, those fibres being Scenario::beams [first_beam, first_beam + m n);
/// penalty 0 (auto), line yarn.line. Without, none.
std::vector<BodySpec> yarn_bodies(const YarnSpec& yarn, int first_beam);

/// Appends `yarn` to scenario.yarns, its fibres to scenario.beams and its bodies to scenario.bodies, and
/// sets its first_beam and first_body to where they went. Checks nothing: validate() does.
void append_yarn(Scenario& scenario, YarnSpec yarn);

/// For each beam of `scenario`, whether a yarn made it (the range first_beam.. of a yarn).
std::vector<bool> beams_made_by_yarns(const Scenario& scenario);

/// For each body of `scenario`, whether a yarn made it.
std::vector<bool> bodies_made_by_yarns(const Scenario& scenario);

}  // namespace nodus::scenario
