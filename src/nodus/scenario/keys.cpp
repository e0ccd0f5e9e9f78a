#include "nodus/scenario/keys.hpp"

#include <array>
#include <cctype>
#include <stdexcept>
#include <string>

#include "nodus/scenario/scenario.hpp"

namespace nodus::scenario {

namespace {

// clang-format off
constexpr std::array kKeys{
  // path, type, unit, default, range, help
  KeyDoc{"units", "map", "", "-", "",
         "the unit system; if present, each of its keys must have exactly the value shown"},
  KeyDoc{"units.length", "choice", "", "mm", "mm", "length unit"},
  KeyDoc{"units.force", "choice", "", "N", "N", "force unit"},
  KeyDoc{"units.stress", "choice", "", "MPa", "MPa", "stress unit"},
  KeyDoc{"units.time", "choice", "", "s", "s", "time unit"},

  KeyDoc{"materials", "list", "", "required", "non-empty", "the isotropic elastic materials"},
  KeyDoc{"materials[].name", "string", "", "required", "unique among materials",
         "name by which beams refer to the material"},
  KeyDoc{"materials[].young_modulus", "number", "MPa", "required", "> 0", "Young's modulus E"},
  KeyDoc{"materials[].poisson_ratio", "number", "", "required", "in [0, 0.5)",
         "Poisson's ratio nu; the shear modulus is E / (2 (1 + nu))"},

  KeyDoc{"beams", "list", "", "required", "non-empty",
         "the beams, each straight in its reference configuration"},
  KeyDoc{"beams[].name", "string", "", "required", "unique among beams",
         "name by which conditions refer to the beam"},
  KeyDoc{"beams[].material", "string", "", "required", "naming a material", "the beam's material"},
  KeyDoc{"beams[].radius", "number", "mm", "required", "> 0", "radius of the circular cross-section"},
  KeyDoc{"beams[].length", "number", "mm", "required", "> 0", "length of the beam axis"},
  KeyDoc{"beams[].elements", "integer", "", "required", ">= 1",
         "number of 3-node quadratic elements; the beam has nodes 0 .. 2 elements"},
  KeyDoc{"beams[].start", "vector", "mm", "[0, 0, 0]", "", "centre of the first end section"},
  KeyDoc{"beams[].direction", "vector", "", "[1, 0, 0]", "with nonzero length",
         "axis direction from start to end; normalised by the reader"},
  KeyDoc{"beams[].director1", "vector", "", "auto", "not parallel to direction",
         "first section director; orthogonalised against direction and normalised. auto: the coordinate "
         "axis least parallel to direction, orthogonalised"},
  KeyDoc{"beams[].bending_factor", "number", "", "1", "> 0",
         "multiplies the second moment of area in bending (Table 1 of the paper uses 0.3)"},

  KeyDoc{"conditions", "list", "", "[]", "", "named boundary conditions, each on one cross-section"},
  KeyDoc{"conditions[].name", "string", "", "required", "unique among conditions",
         "name by which stages refer to the condition"},
  KeyDoc{"conditions[].type", "choice", "", "required", "clamp | motion | rigid | load",
         "clamp: keep the dofs at their values on activation; motion: prescribed translation and rotation; "
         "rigid: the whole beam follows a rigid motion (a tool beam, never released); load: force and moment"},
  KeyDoc{"conditions[].beam", "string", "", "required", "naming a beam", "the beam the condition acts on"},
  KeyDoc{"conditions[].at", "choice", "", "required", "start | end | an integer in [0, 2 elements]",
         "the cross-section: start (node 0), end (node 2 elements) or a local node index; not on rigid"},
  KeyDoc{"conditions[].pivot", "vector", "mm", "-", "motion and rigid only",
         "the fixed point the prescribed rotation turns the section centres about, r = p + u + Q (r0 - p); "
         "default: the section centre (motion), the centre of the beam's middle node at activation (rigid)"},
  KeyDoc{"conditions[].dofs", "list", "", "[all]",
         "of at least one of all | position | directors | x | y | z | g1x | g1y | g1z | g2x | g2y | g2z",
         "clamp and motion only: the constrained dofs, the union of the items (position = x, y, z; "
         "directors = the six g*)"},
  KeyDoc{"conditions[].active", "bool", "", "true", "", "active from the first stage on"},
  KeyDoc{"conditions[].force", "vector", "N", "[0, 0, 0]", "",
         "load only: initial dead force on the section centre"},
  KeyDoc{"conditions[].moment", "vector", "N mm", "[0, 0, 0]", "",
         "load only: initial moment about the fixed axis of its vector"},

  KeyDoc{"stages", "list", "", "required", "non-empty", "the loading program, run in order"},
  KeyDoc{"stages[].name", "string", "", "required", "unique among stages", "name shown in progress output"},
  KeyDoc{"stages[].steps", "integer", "", "required", ">= 1", "number of nominal load steps"},
  KeyDoc{"stages[].duration", "number", "s", "1", "> 0", "length of the stage in load time"},
  KeyDoc{"stages[].stabilization", "number", "N s/mm^2", "0", ">= 0",
         "viscous drag per unit length on the beams during the stage, force = -value * (velocity in load "
         "time) on the axis and value * R^2/4 on each director; a numerical aid to pass snap-throughs, off (0) "
         "or vanished (the beams at rest) where results are read (docs/model.md)"},
  KeyDoc{"stages[].stabilization_end", "number", "N s/mm^2", "stabilization", ">= 0",
         "the drag at the stage end, reached geometrically from stabilization; 0: decays to 1e-6 of it and is "
         "exactly 0 at the stage end"},
  KeyDoc{"stages[].activate", "list", "", "[]", "of condition names",
         "conditions switched on at the start of the stage"},
  KeyDoc{"stages[].release", "list", "", "[]", "of condition names, none also in activate",
         "conditions switched off at the start of the stage"},
  KeyDoc{"stages[].contact_off", "list", "", "[]", "of contact beam names",
         "beams taken out of contact at the start of the stage (a tool removed); they stay where they are"},
  KeyDoc{"stages[].contact_on", "list", "", "[]", "of contact beam names, none also in contact_off",
         "beams put back into contact at the start of the stage"},
  KeyDoc{"stages[].motions", "map", "", "{}", "from motion or rigid condition names to targets",
         "prescribed motions reached during the stage"},
  KeyDoc{"stages[].motions.<condition>", "map", "", "required", "with translation/rotation or keyframes",
         "the target of one motion condition"},
  KeyDoc{"stages[].motions.<condition>.translation", "vector", "mm", "[0, 0, 0]", "",
         "short form: translation of the section centre at stage end, cumulative since activation"},
  KeyDoc{"stages[].motions.<condition>.rotation", "vector", "deg", "[0, 0, 0]", "",
         "short form: rotation vector of the section at stage end, cumulative since activation"},
  KeyDoc{"stages[].motions.<condition>.keyframes", "list", "", "-",
         "non-empty, not next to translation or rotation", "long form: keyframes inside the stage"},
  KeyDoc{"stages[].motions.<condition>.keyframes[].at", "number", "", "required",
         "in (0, 1], increasing, the last one = 1", "fraction of the stage at which the keyframe is reached"},
  KeyDoc{"stages[].motions.<condition>.keyframes[].translation", "vector", "mm", "[0, 0, 0]", "",
         "translation of the section centre, cumulative since activation"},
  KeyDoc{"stages[].motions.<condition>.keyframes[].rotation", "vector", "deg", "[0, 0, 0]", "",
         "rotation vector of the section, cumulative since activation"},
  KeyDoc{"stages[].loads", "map", "", "{}", "from load condition names to targets",
         "load values reached at the end of the stage"},
  KeyDoc{"stages[].loads.<condition>", "map", "", "required", "with force and/or moment",
         "the target of one load condition"},
  KeyDoc{"stages[].loads.<condition>.force", "vector", "N", "unchanged", "",
         "force at stage end; omitted: keeps its value at stage start"},
  KeyDoc{"stages[].loads.<condition>.moment", "vector", "N mm", "unchanged",
         "parallel to the load's other nonzero moments",
         "moment at stage end; omitted: keeps its value at stage start"},

  KeyDoc{"solver", "map", "", "{}", "", "Newton solver settings"},
  KeyDoc{"solver.linear_solver", "choice", "", "cholmod", "cholmod | umfpack",
         "sparse direct solver: cholmod (Cholesky) or umfpack (LU)"},
  KeyDoc{"solver.max_newton_iterations", "integer", "", "25", ">= 1", "iterations per step attempt"},
  KeyDoc{"solver.residual_tolerance", "number", "", "1e-8", "> 0",
         "converged when the residual norm <= tolerance times the force scale"},
  KeyDoc{"solver.increment_tolerance", "number", "", "1e-6", "> 0",
         "converged when the largest increment <= tolerance times the length scale"},
  KeyDoc{"solver.max_cutbacks", "integer", "", "12", ">= 0",
         "successive halvings of a step before giving up"},
  KeyDoc{"solver.easy_iterations", "integer", "", "4", ">= 1",
         "a step converged in at most this many iterations lets the next step grow"},
  KeyDoc{"solver.line_search", "bool", "", "false", "", "damp Newton updates by a line search on the energy slope (off: faster on every verification case, docs/model.md)"},
  KeyDoc{"solver.gauss_points", "integer", "", "2", "in 1..5", "Gauss points per element along the axis (2: reduced integration, free of locking; docs/model.md)"},
  KeyDoc{"solver.fold_stiffness", "number", "", "0", ">= 0", "beta of the energy that keeps a 2-point element from folding back on itself at no cost; 0: none (docs/model.md)"},

  KeyDoc{"output", "map", "", "{}", "", "output settings"},
  KeyDoc{"output.vtk_every", "integer", "", "1", ">= 0",
         "write a VTK file every N converged steps; 0: the final state only"},
  KeyDoc{"output.tube_sides", "integer", "", "12", ">= 3", "facets around each tube in the VTK output"},
  KeyDoc{"output.progress_seconds", "number", "s", "1", ">= 0",
         "minimum interval between progress lines on stderr"},
  KeyDoc{"output.contact_csv", "bool", "", "false", "",
         "with contact: also write contact/contact_NNNNNN.csv (every contact element) at every VTK "
         "output step"},
  KeyDoc{"output.checkpoint_every", "integer", "", "0", ">= 0",
         "also save the run's complete state every N converged steps, as checkpoints/latest.nodus-state "
         "(the state at the end of every stage is always saved; docs/output.md); 0: at stage ends only"},

  KeyDoc{"contact", "map", "", "-", "",
         "contact detection and contact forces between the beams (docs/contact.md); absent: no contact, "
         "present (even empty): on. The detection lengths are the paper's delta_prox, delta_separ, h_dist, "
         "l_p, h_c (Durville 2012, Eq. 24-48); auto ones are derived when the run starts, with R the "
         "largest radius of the contact beams"},
  KeyDoc{"contact.enabled", "bool", "", "true", "", "false: contact is off although the section is present"},
  KeyDoc{"contact.self_contact", "bool", "", "true", "",
         "also detect contact between separate parts of one beam"},
  KeyDoc{"contact.beams", "list", "", "all beams", "of beam names, non-empty, each beam once",
         "the beams that take part in contact"},
  KeyDoc{"contact.proximity_distance", "number", "mm", "auto", "> 0 or auto",
         "delta_prox: largest axis-to-axis distance of a proximity (candidate contact). auto: 3 R, i.e. 1.5 "
         "times the contact distance 2 R"},
  KeyDoc{"contact.separation_distance", "number", "mm", "auto", "> 0 or auto, > proximity_distance",
         "delta_separ: smallest distance along one beam between two of its parts paired for self contact. "
         "auto: 4 proximity_distance"},
  KeyDoc{"contact.test_point_spacing", "number", "mm", "auto", "> 0 or auto",
         "h_dist: spacing of the test points along each beam. auto: sqrt(proximity_distance^2 - (2 R)^2), "
         "at least proximity_distance / 2"},
  KeyDoc{"contact.matching_length", "number", "mm", "auto", "> 0 or auto, >= test_point_spacing",
         "l_p: length of an elementary matching interval. auto: 2 test_point_spacing"},
  KeyDoc{"contact.element_spacing", "number", "mm", "auto", "> 0 or auto",
         "h_c: spacing of the contact elements along a proximity zone. auto: h / 2, h the smaller element "
         "length of the zone's two beams"},
  KeyDoc{"contact.forces", "bool", "", "true", "",
         "apply contact forces (Durville 2012, Sect. 5); false: detect and write out only"},
  KeyDoc{"contact.penalty", "number", "N/mm", "auto", "> 0 or auto",
         "initial penalty coefficient k_c of every proximity zone (Eq. 53), then adjusted per zone so that "
         "the largest penetration approaches max_penetration (Eq. 54). auto: E R, with E the smallest "
         "Young's modulus and R the smallest radius of the contact beams"},
  KeyDoc{"contact.max_penetration", "number", "mm", "auto", "> 0 or auto",
         "p_max, the penetration the per-zone penalty adjustment aims at (Eq. 54). auto: 0.02 R (R the "
         "smallest radius)"},
  KeyDoc{"contact.regularization", "number", "mm", "auto", "> 0 or auto",
         "p_reg, the depth of the quadratic start of the penalty law (Eq. 53). auto: max_penetration / 10"},
  KeyDoc{"contact.friction", "number", "", "0", ">= 0",
         "Coulomb friction coefficient mu (Eq. 55-64); 0: frictionless"},
  KeyDoc{"contact.max_reversible_slip", "number", "mm", "auto", "> 0 or auto",
         "g_rev_max, the tangential displacement taken reversibly before sliding (regularised Coulomb law). "
         "auto: max_penetration / 2"},
  KeyDoc{"contact.friction_tangent", "choice", "", "frozen", "frozen | varying",
         "how Newton's tangent linearises the friction force (the force is the same). frozen: R_N held fixed, "
         "a symmetric tangent. varying: the exact derivative with R_N varying, not symmetric: needs "
         "solver.linear_solver: umfpack (docs/contact.md)"},
  KeyDoc{"contact.particles", "choice", "", "fixed", "fixed | facing",
         "where the contact forces act during Newton. fixed: the paper's particles, material points of the "
         "section borders placed at detection (Eq. 37-40). facing: at each evaluation, the points of the "
         "borders that face each other along the normal (no spurious torsional stiffness from the lever arm "
         "of a turned section; for tightened knots)"},
  KeyDoc{"contact.max_detections", "integer", "", "4", ">= 1",
         "loop 2 of the global algorithm (Sect. 6): at most this many detections of the contact elements "
         "per load step"},
  KeyDoc{"contact.max_normal_iterations", "integer", "", "6", ">= 1",
         "loop 3: at most this many updates of the normal directions and penalties per detection"},
  KeyDoc{"contact.normal_tolerance", "number", "rad", "0.001", "> 0",
         "loop 3 stops when an update turns no normal by more than this and leaves every zone's penalty as "
         "it is: its largest penetration in [max_penetration / 2, max_penetration], or below "
         "max_penetration / 1000 (a zone that only touches)"},

  KeyDoc{"branches", "list", "", "[]", "-",
         "runs that each continue from the state at the end of one stage of stages, after all of stages; "
         "results in DIR/branches/NAME"},
  KeyDoc{"branches[].name", "string", "", "required", "unique among branches, of letters, digits, _ . -",
         "name of the branch and of its output folder DIR/branches/NAME"},
  KeyDoc{"branches[].from", "string", "", "required", "naming a stage of stages",
         "the branch starts from the state at the end of this stage (load time and step numbers go on "
         "from there)"},
  KeyDoc{"branches[].contact", "map", "", "-", "with friction only; needs a contact section",
         "overrides of the contact settings for the branch's stages"},
  KeyDoc{"branches[].contact.friction", "number", "", "unchanged", ">= 0",
         "Coulomb friction coefficient mu of the branch's stages"},
  KeyDoc{"branches[].stages", "list", "", "required", "non-empty, each item as in stages[]",
         "the branch's loading program, run in order after the from stage; stage names unique within the "
         "branch"},
};
// clang-format on

std::string type_phrase(std::string_view type) {
  if (type == "number") return "a number";
  if (type == "integer") return "an integer";
  if (type == "string") return "a string";
  if (type == "bool") return "true or false";
  if (type == "vector") return "a list of 3 numbers";
  if (type == "list") return "a list";
  if (type == "map") return "a map";
  return std::string(type);
}

/// Markdown table cell: "|" must be escaped.
std::string cell(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::span<const KeyDoc> scenario_keys() {
  return kKeys;
}

const KeyDoc& scenario_key(std::string_view path) {
  for (const KeyDoc& key : kKeys) {
    if (key.path == path) return key;
  }
  throw std::logic_error("nodus::scenario: key '" + std::string(path) + "' is missing from the key table");
}

std::string_view parent_pattern(std::string_view path) {
  const auto dot = path.rfind('.');
  return dot == std::string_view::npos ? std::string_view{} : path.substr(0, dot);
}

std::string_view leaf_name(std::string_view path) {
  const auto dot = path.rfind('.');
  return dot == std::string_view::npos ? path : path.substr(dot + 1);
}

std::string expected_text(const KeyDoc& key) {
  std::string text;
  if (key.type == "choice") {
    text = key.range.find('|') == std::string_view::npos ? "exactly " : "one of ";
    text += key.range;
  } else {
    text = type_phrase(key.type);
    if (!key.range.empty()) {
      // Comparisons, intervals and "of ..." read as a continuation, anything else after a comma.
      const char first = key.range.front();
      const bool continues = first == '<' || first == '>' || first == '=' || first == '[' || first == '(' ||
                             std::isdigit(static_cast<unsigned char>(first)) ||
                             key.range.starts_with("in ") || key.range.starts_with("of ") ||
                             key.range.starts_with("with ") || key.range.starts_with("from ") ||
                             key.range.starts_with("naming ") || key.range.starts_with("not ") ||
                             key.range.starts_with("unique ") || key.range.starts_with("parallel ");
      text += continues ? " " : ", ";
      text += key.range;
    }
  }
  if (!key.unit.empty()) {
    text += " (";
    text += key.unit;
    text += ")";
  }
  return text;
}

std::string scenario_keys_markdown() {
  std::string out =
      "| Key | Type | Unit | Default | Range | Description |\n"
      "|-----|------|------|---------|-------|-------------|\n";
  for (const KeyDoc& key : kKeys) {
    out += "| `";
    out += key.path;
    out += "` | ";
    out += key.type;
    out += " | ";
    out += cell(key.unit.empty() ? "-" : key.unit);
    out += " | ";
    out += cell(key.default_value);
    out += " | ";
    out += cell(key.range.empty() ? "-" : key.range);
    out += " | ";
    out += cell(key.help);
    out += " |\n";
  }
  return out;
}

}  // namespace nodus::scenario
