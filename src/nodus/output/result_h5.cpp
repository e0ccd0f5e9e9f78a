#include "nodus/output/result_h5.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "nodus/beam/strain_measures.hpp"
#include "nodus/output/atomic_file.hpp"
#include "nodus/output/contact_csv_writer.hpp"
#include "nodus/output/contact_table.hpp"
#include "nodus/output/hdf5_io.hpp"
#include "nodus/output/provenance.hpp"
#include "nodus/output/steps_csv_writer.hpp"
#include "nodus/scenario/describe.hpp"
#include "nodus/version.hpp"

namespace nodus::output {

namespace {

using hdf5::Handle;

/// The columns of steps.csv that hold whole numbers (stored as int64); `stage` and `cutback_causes` hold
/// text; every other column is a float64 (an empty field, as a condition's before it acts, is NaN).
bool integer_column(const std::string& name) {
  static const std::set<std::string> names = {
      "step",       "newton_iterations", "cutbacks", "zones",           "contact_elements",
      "detections", "normal_iterations", "slipping", "loops_converged", "entered",
      "left",       "to_slip",           "to_stick"};
  return names.contains(name);
}

bool text_column(const std::string& name) {
  return name == "stage" || name == "cutback_causes";
}

/// An HDF5 link name for a column name: '/' separates groups, so it becomes '_'; "." is not a name.
std::string link_name(std::string name) {
  std::replace(name.begin(), name.end(), '/', '_');
  return name == "." ? "_" : name;
}

/// "000012" for step 12: the state group's name.
std::string state_name(int step) {
  return fmt::format("{:06d}", step);
}

/// The name of the stage the initial state of `sim` belongs to: the first stage for step 0; for a state
/// restored at a stage end (a branch), that stage; inside a stage, that stage.
std::string initial_stage(const simulation::Simulation& sim) {
  const auto& stages = sim.scenario().stages;
  if (stages.empty()) return {};
  int stage = sim.progress().stage;
  if (sim.steps() > 0 && !sim.progress().stage_begun) --stage;
  stage = std::clamp(stage, 0, static_cast<int>(stages.size()) - 1);
  return stages[static_cast<std::size_t>(stage)].name;
}

/// The step table's columns from its rows, written as /steps (replaced).
void write_steps(hid_t root, const std::vector<std::string>& header,
                 const std::vector<std::vector<std::string>>& rows) {
  hdf5::remove_link(root, "steps");
  Handle group = hdf5::require_group(root, "steps");
  for (std::size_t c = 0; c < header.size(); ++c) {
    const std::string& name = header[c];
    auto field = [&](const std::vector<std::string>& row) -> std::string {
      return c < row.size() ? row[c] : std::string();
    };
    if (text_column(name)) {
      std::vector<std::string> values;
      for (const auto& row : rows) values.push_back(field(row));
      hdf5::write_strings(group.get(), link_name(name), values);
    } else if (integer_column(name)) {
      std::vector<std::int64_t> values;
      for (const auto& row : rows) {
        const std::string f = field(row);
        values.push_back(f.empty() ? 0 : std::stoll(f));
      }
      hdf5::write_ints(group.get(), link_name(name), values);
    } else {
      std::vector<double> values;
      for (const auto& row : rows) {
        const std::string f = field(row);
        values.push_back(f.empty() ? std::numeric_limits<double>::quiet_NaN() : std::stod(f));
      }
      hdf5::write_doubles(group.get(), link_name(name), values);
    }
  }
}

/// The number columns of the contact element table after `zone`, `beam_i` and `beam_j`, in the order of
/// contact_final.csv (contact_table.hpp); `forces`: only in a state with contact forces.
struct ContactColumn {
  const char* name;
  double (*value)(const ContactRow&);
  bool forces;
};
// clang-format off
const ContactColumn kContactColumns[] = {
    {"zeta", [](const ContactRow& r) { return r.zeta; }, false},
    {"abscissa_i", [](const ContactRow& r) { return r.abscissa_i; }, false},
    {"abscissa_j", [](const ContactRow& r) { return r.abscissa_j; }, false},
    {"xi1_i", [](const ContactRow& r) { return r.transverse_i.x(); }, false},
    {"xi2_i", [](const ContactRow& r) { return r.transverse_i.y(); }, false},
    {"xi1_j", [](const ContactRow& r) { return r.transverse_j.x(); }, false},
    {"xi2_j", [](const ContactRow& r) { return r.transverse_j.y(); }, false},
    {"x_i", [](const ContactRow& r) { return r.position_i.x(); }, false},
    {"y_i", [](const ContactRow& r) { return r.position_i.y(); }, false},
    {"z_i", [](const ContactRow& r) { return r.position_i.z(); }, false},
    {"x_j", [](const ContactRow& r) { return r.position_j.x(); }, false},
    {"y_j", [](const ContactRow& r) { return r.position_j.y(); }, false},
    {"z_j", [](const ContactRow& r) { return r.position_j.z(); }, false},
    {"nx", [](const ContactRow& r) { return r.normal.x(); }, false},
    {"ny", [](const ContactRow& r) { return r.normal.y(); }, false},
    {"nz", [](const ContactRow& r) { return r.normal.z(); }, false},
    {"gap", [](const ContactRow& r) { return r.gap; }, false},
    {"normal_force", [](const ContactRow& r) { return r.normal_force; }, true},
    {"tangential_force", [](const ContactRow& r) { return r.tangential_force; }, true},
    {"tx", [](const ContactRow& r) { return r.tangential.x(); }, true},
    {"ty", [](const ContactRow& r) { return r.tangential.y(); }, true},
    {"tz", [](const ContactRow& r) { return r.tangential.z(); }, true},
};
// clang-format on

/// /states/NNNNNN/contact and /zones: the contact element and zone tables of `geometry`, column by column
/// as contact_final.csv and zones_final.csv hold them (beam_i, beam_j as beam indices), with the forces of
/// `states` where given (then also the `state` column: open, stick or slip).
void write_contact(hid_t state, const contact::ContactGeometry& geometry,
                   const std::vector<simulation::ContactState>* states) {
  check_contact_geometry(geometry, "result.h5");
  check_contact_states(geometry, states, "result.h5");
  std::vector<ContactRow> rows;
  for (std::size_t k = 0; k < geometry.elements.size(); ++k) rows.push_back(contact_row(geometry, k, states));
  auto ints = [&](auto field) {
    std::vector<std::int64_t> out;
    for (const ContactRow& r : rows) out.push_back(field(r));
    return out;
  };
  Handle group = hdf5::require_group(state, "contact");
  hdf5::write_ints(group.get(), "zone", ints([](const ContactRow& r) { return r.zone; }));
  hdf5::write_ints(group.get(), "beam_i", ints([](const ContactRow& r) { return r.beam_i; }));
  hdf5::write_ints(group.get(), "beam_j", ints([](const ContactRow& r) { return r.beam_j; }));
  for (const ContactColumn& column : kContactColumns) {
    if (column.forces && !states) continue;
    std::vector<double> values;
    for (const ContactRow& r : rows) values.push_back(column.value(r));
    hdf5::write_doubles(group.get(), column.name, values);
  }
  if (states) {
    std::vector<std::string> status;
    for (const ContactRow& r : rows) status.emplace_back(status_name(r.status));
    hdf5::write_strings(group.get(), "state", status);
  }

  std::vector<std::int64_t> zone_index, zone_i, zone_j, elements;
  std::vector<double> a, b, c, d, min_gap;
  for (std::size_t z = 0; z < geometry.zones.size(); ++z) {
    const contact::ProximityZone& pz = geometry.zones[z];
    zone_index.push_back(static_cast<std::int64_t>(z));
    zone_i.push_back(pz.beam_i);
    zone_j.push_back(pz.beam_j);
    a.push_back(pz.a);
    b.push_back(pz.b);
    c.push_back(pz.c);
    d.push_back(pz.d);
    elements.push_back(pz.num_elements);
    min_gap.push_back(smallest_gap(geometry, pz).value_or(std::numeric_limits<double>::quiet_NaN()));
  }
  Handle zones = hdf5::require_group(state, "zones");
  hdf5::write_ints(zones.get(), "zone", zone_index);
  hdf5::write_ints(zones.get(), "beam_i", zone_i);
  hdf5::write_ints(zones.get(), "beam_j", zone_j);
  hdf5::write_doubles(zones.get(), "a", a);
  hdf5::write_doubles(zones.get(), "b", b);
  hdf5::write_doubles(zones.get(), "c", c);
  hdf5::write_doubles(zones.get(), "d", d);
  hdf5::write_ints(zones.get(), "contact_elements", elements);
  hdf5::write_doubles(zones.get(), "min_gap", min_gap);
}

/// Closes `file`, flushing it; throws WriteError naming `path` if HDF5 could not.
void close(Handle& file, const std::filesystem::path& path) {
  if (!file.reset())
    throw WriteError(fmt::format("cannot write '{}': HDF5 could not flush it", path.string()));
}

}  // namespace

std::vector<std::vector<std::string>> split_csv(const std::string& text) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (quoted) {
      if (ch == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (ch == '"') {
        quoted = false;
      } else {
        field += ch;
      }
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      record.push_back(std::move(field));
      field.clear();
    } else if (ch == '\n') {
      record.push_back(std::move(field));
      field.clear();
      records.push_back(std::move(record));
      record.clear();
    } else {
      field += ch;
    }
  }
  return records;
}

ResultH5Writer::ResultH5Writer(std::filesystem::path dir, int every, bool enabled)
    : dir_(std::move(dir)), every_(every), enabled_(enabled) {
  if (every_ < 0) throw std::invalid_argument(fmt::format("result.h5: every = {}, must be >= 0", every_));
}

void ResultH5Writer::on_start(const simulation::Simulation& sim) {
  active_ = enabled_ && sim.scenario().output.hdf5;
  steps_.clear();
  times_.clear();
  rows_.clear();
  if (!active_) {
    // A result of an earlier run with output.hdf5 would not match this run's other files.
    std::error_code ignored;
    std::filesystem::remove(path(), ignored);
    std::filesystem::remove(xdmf_path(), ignored);
    return;
  }
  std::vector<std::string> conditions;
  for (int c = 0; c < sim.conditions().size(); ++c) conditions.push_back(sim.conditions().name(c));
  std::vector<std::string> bodies;
  for (const model::RigidBody& b : sim.model().bodies()) bodies.push_back(b.name);
  step_header_ = split_csv(steps_csv_header(conditions, bodies) + "\n").front();
  num_nodes_ = sim.model().num_nodes();
  num_segments_ = 0;
  for (const beam::Beam& b : sim.model().beams()) num_segments_ += b.num_nodes() - 1;
  last_step_ = sim.steps();
  stage_ = initial_stage(sim);
  if (sim.start_kind() == simulation::StartKind::resumed) {
    resume(sim, last_step_);
    return;
  }
  create(sim);
  write_state(sim, last_step_, sim.time(), stage_);
}

void ResultH5Writer::create(const simulation::Simulation& sim) {
  std::error_code error;
  std::filesystem::create_directories(dir_, error);
  if (error) throw_write_error("create folder", dir_, error.value());
  Handle file = hdf5::create_file(path());
  const hid_t root = file.get();
  const scenario::Scenario& s = sim.scenario();
  hdf5::set_attribute(root, "format", std::string(kResultFormat));
  hdf5::set_attribute(root, "format_version", std::int64_t{kResultFormatVersion});
  hdf5::set_attribute(root, "units", std::string("mm, N, MPa, s"));
  hdf5::set_attribute(root, "run", s.origin ? s.origin->name : std::string("main"));
  hdf5::set_attribute(root, "nodus", std::string(nodus::version()));
  hdf5::set_attribute(root, "commit", std::string(nodus::commit()));
  hdf5::write_text(root, "scenario", scenario::describe(s));

  // The beams, in scenario order; a tool is a beam that a `rigid` condition moves.
  const model::Model& model = sim.model();
  std::vector<std::string> names;
  std::vector<double> radius, young;
  std::vector<std::int64_t> first, count, tool, segments, node_beam;
  for (std::size_t b = 0; b < model.beams().size(); ++b) {
    const beam::Beam& beam = model.beams()[b];
    names.push_back(beam.name());
    radius.push_back(beam.radius());
    const int material = b < s.beams.size() ? s.beams[b].material : -1;
    young.push_back(material >= 0 && material < static_cast<int>(s.materials.size())
                        ? s.materials[static_cast<std::size_t>(material)].young_modulus
                        : std::numeric_limits<double>::quiet_NaN());
    first.push_back(beam.first_node());
    count.push_back(beam.num_nodes());
    const bool moved = std::any_of(s.conditions.begin(), s.conditions.end(), [&](const auto& c) {
      return c.type == scenario::ConditionType::rigid && c.bodies.empty() && c.beam == static_cast<int>(b);
    });
    tool.push_back(moved ? 1 : 0);
    for (int i = 0; i < beam.num_nodes(); ++i) node_beam.push_back(static_cast<std::int64_t>(b));
    for (int i = 0; i + 1 < beam.num_nodes(); ++i) {
      segments.push_back(beam.node(i));
      segments.push_back(beam.node(i + 1));
    }
  }
  {
    Handle beams = hdf5::require_group(root, "beams");
    hdf5::write_strings(beams.get(), "name", names);
    hdf5::write_doubles(beams.get(), "radius", radius);
    hdf5::write_doubles(beams.get(), "young_modulus", young);
    hdf5::write_ints(beams.get(), "first_node", first);
    hdf5::write_ints(beams.get(), "node_count", count);
    hdf5::write_ints(beams.get(), "tool", tool);
    Handle mesh = hdf5::require_group(root, "mesh");
    hdf5::write_int_matrix(mesh.get(), "segments", segments, 2);
    hdf5::write_ints(mesh.get(), "node_beam", node_beam);
  }
  {
    std::vector<std::string> stage_names;
    std::vector<double> start, end;
    for (std::size_t k = 0; k < s.stages.size(); ++k) {
      stage_names.push_back(s.stages[k].name);
      start.push_back(k == 0 ? 0.0 : sim.stage_end_time(static_cast<int>(k) - 1));
      end.push_back(sim.stage_end_time(static_cast<int>(k)));
    }
    Handle stages = hdf5::require_group(root, "stages");
    hdf5::write_strings(stages.get(), "name", stage_names);
    hdf5::write_doubles(stages.get(), "start_time", start);
    hdf5::write_doubles(stages.get(), "end_time", end);
  }
  hdf5::require_group(root, "states");
  // Each branch writes its own DIR/branches/NAME/result.h5; the links resolve once it exists.
  if (!s.origin && !s.branches.empty()) {
    Handle branches = hdf5::require_group(root, "branches");
    for (const scenario::BranchSpec& branch : s.branches) {
      const std::string target = "branches/" + branch.name + "/result.h5";
      if (H5Lcreate_external(target.c_str(), "/", branches.get(), link_name(branch.name).c_str(), H5P_DEFAULT,
                             H5P_DEFAULT) < 0)
        throw WriteError(
            fmt::format("cannot write '{}': HDF5 could not link branch '{}'", path().string(), branch.name));
    }
  }
  write_steps(root, step_header_, rows_);
  close(file, path());
}

void ResultH5Writer::resume(const simulation::Simulation& sim, int last_step) {
  // The step table as steps.csv now holds it (StepsCsvWriter, an earlier observer, has cut it at the resumed
  // step).
  if (std::ifstream in(dir_ / "steps.csv", std::ios::binary); in) {
    std::ostringstream text;
    text << in.rdbuf();
    auto records = split_csv(steps_csv_up_to(text.str(), last_step));
    if (!records.empty()) records.erase(records.begin());  // the header
    rows_ = std::move(records);
  }
  if (!rows_.empty() && rows_.back().size() > 1) stage_ = rows_.back()[1];

  bool kept = false;
  if (std::optional<Handle> file = hdf5::open_file(path(), true)) {
    try {
      const hid_t root = file->get();
      if (hdf5::string_attribute(root, "format", path().string()) != kResultFormat)
        throw std::runtime_error("another format");
      Handle states = hdf5::open_group(root, "states", "the output states");
      std::vector<std::pair<int, double>> found;
      for (const std::string& name : hdf5::link_names(states.get())) {
        Handle state = hdf5::open_group(states.get(), name, "an output state");
        const auto step = static_cast<int>(hdf5::int_attribute(state.get(), "step", path().string()));
        const double time = hdf5::double_attribute(state.get(), "load_time", path().string());
        state.reset();
        if (step > last_step)
          hdf5::remove_link(states.get(), name);
        else
          found.emplace_back(step, time);
      }
      std::sort(found.begin(), found.end());
      for (const auto& [step, time] : found) {
        steps_.push_back(step);
        times_.push_back(time);
      }
      states.reset();
      write_steps(root, step_header_, rows_);
      close(*file, path());
      kept = true;
    } catch (const std::runtime_error&) {
      steps_.clear();
      times_.clear();
    }
  }
  if (!kept) {
    std::error_code error;
    if (std::filesystem::exists(path(), error)) {
      std::filesystem::path damaged = path();
      damaged += ".damaged";
      std::filesystem::rename(path(), damaged, error);
      spdlog::warn(
          "{}: cannot be opened (damaged by a hard kill?): moved aside as {}; a new one holds the "
          "states from step {} on",
          path().string(), damaged.filename().string(), last_step + 1);
    }
    create(sim);
  }
  write_xdmf();
}

void ResultH5Writer::on_step(const simulation::Simulation& sim, const simulation::StepRecord& record) {
  if (!active_) return;
  const auto& stages = sim.scenario().stages;
  stage_ = record.stage >= 0 && record.stage < static_cast<int>(stages.size())
               ? stages[static_cast<std::size_t>(record.stage)].name
               : "";
  rows_.push_back(split_csv(steps_csv_row(record, stage_, sim.conditions().size(),
                                          static_cast<int>(sim.model().bodies().size())) +
                            "\n")
                      .front());
  last_step_ = record.step;
  if (every_ > 0 && record.step % every_ == 0) write_state(sim, record.step, record.time, stage_);
}

void ResultH5Writer::on_finish(const simulation::Simulation& sim, const simulation::RunSummary& summary) {
  if (!active_) return;
  if (steps_.empty() || steps_.back() != last_step_) write_state(sim, last_step_, sim.time(), stage_);
  std::optional<Handle> file = hdf5::open_file(path(), true);
  if (!file) throw WriteError(fmt::format("cannot write '{}': HDF5 cannot open it", path().string()));
  // Where the result came from, as summary.json's provenance.
  const Provenance p = this_process(summary.linear_solvers);
  const hid_t root = file->get();
  hdf5::set_attribute(root, "nodus", p.version);
  hdf5::set_attribute(root, "commit", p.commit);
  hdf5::set_attribute(root, "processor", p.processor);
  hdf5::set_attribute(root, "hardware_threads", std::int64_t{p.hardware_threads});
  hdf5::set_attribute(root, "threads", std::int64_t{p.threads});
  hdf5::set_attribute(root, "mpi_ranks", std::int64_t{p.mpi_ranks});
  hdf5::set_attribute(root, "linear_solvers", p.linear_solvers);
  close(*file, path());
}

void ResultH5Writer::write_state(const simulation::Simulation& sim, int step, double time,
                                 const std::string& stage) {
  // Refused before a byte is written where the disk has not room for it (at most the state's values, the
  // step table and HDF5's object headers; compression only saves), so that a full disk leaves the file whole.
  const auto state_values =
      static_cast<std::uintmax_t>(sim.model().num_nodes()) * (4 * 3 + beam::kNumStrains) +
      (sim.contact() ? sim.contact()->elements.size() * 30 + sim.contact()->zones.size() * 9 : 0) +
      rows_.size() * step_header_.size();
  require_space(dir_, 2 * 8 * state_values + 64 * 1024, path());
  std::optional<Handle> file = hdf5::open_file(path(), true);
  if (!file) throw WriteError(fmt::format("cannot write '{}': HDF5 cannot open it", path().string()));
  try {
    const hid_t root = file->get();
    Handle states = hdf5::require_group(root, "states");
    const std::string name = state_name(step);
    hdf5::remove_link(states.get(), name);
    Handle group = hdf5::require_group(states.get(), name);
    hdf5::set_attribute(group.get(), "step", std::int64_t{step});
    hdf5::set_attribute(group.get(), "load_time", time);
    hdf5::set_attribute(group.get(), "stage", stage);

    const model::Model& model = sim.model();
    const Eigen::VectorXd& x = sim.state();
    const Eigen::VectorXd& ref = model.reference();
    const int n = model.num_nodes();
    std::vector<double> centre, g1, g2, displacement;
    for (auto* v : {&centre, &g1, &g2, &displacement}) v->reserve(static_cast<std::size_t>(3 * n));
    for (int node = 0; node < n; ++node) {
      const Eigen::Index f = model.node_dof(node);
      for (int c = 0; c < 3; ++c) {
        centre.push_back(x[f + c]);
        g1.push_back(x[f + 3 + c]);
        g2.push_back(x[f + 6 + c]);
        displacement.push_back(x[f + c] - ref[f + c]);
      }
    }
    hdf5::write_matrix(group.get(), "centre", centre, 3);
    hdf5::write_matrix(group.get(), "g1", g1, 3);
    hdf5::write_matrix(group.get(), "g2", g2, 3);
    hdf5::write_matrix(group.get(), "displacement", displacement, 3);
    // The fifteen strain measures, node by node as the VTK files carry them.
    const auto strains = model.node_strains(x);
    for (int k = 0; k < beam::kNumStrains; ++k) {
      std::vector<double> values(static_cast<std::size_t>(n));
      for (int node = 0; node < n; ++node) values[static_cast<std::size_t>(node)] = strains(k, node);
      hdf5::write_doubles(group.get(), beam::strain_name(k), values);
    }
    if (const contact::ContactGeometry* geometry = sim.contact())
      write_contact(group.get(), *geometry, contact_states_to_write(sim));
    group.reset();
    states.reset();
    write_steps(root, step_header_, rows_);
  } catch (const WriteError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw WriteError(e.what());
  }
  close(*file, path());
  const auto at = std::lower_bound(steps_.begin(), steps_.end(), step);
  const auto k = at - steps_.begin();
  if (at != steps_.end() && *at == step) {
    times_[static_cast<std::size_t>(k)] = time;
  } else {
    steps_.insert(at, step);
    times_.insert(times_.begin() + k, time);
  }
  write_xdmf();
}

void ResultH5Writer::write_xdmf() const {
  // XDMF 3: a temporal collection of one grid per state, all reading their arrays from result.h5.
  fmt::memory_buffer out;
  auto put = [&](std::string_view format, auto&&... args) {
    fmt::vformat_to(std::back_inserter(out), format, fmt::make_format_args(args...));
  };
  put("<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n");
  put("    <Grid Name=\"nodus\" GridType=\"Collection\" CollectionType=\"Temporal\">\n");
  const std::string n = std::to_string(num_nodes_);
  for (std::size_t s = 0; s < steps_.size(); ++s) {
    const std::string at = "result.h5:/states/" + state_name(steps_[s]);
    put("      <Grid Name=\"step_{}\" GridType=\"Uniform\">\n", state_name(steps_[s]));
    put("        <Time Value=\"{:.17g}\"/>\n", times_[s]);
    put("        <Topology TopologyType=\"Polyline\" NodesPerElement=\"2\" NumberOfElements=\"{}\">\n",
        num_segments_);
    put("          <DataItem Dimensions=\"{} 2\" NumberType=\"Int\" Precision=\"8\" "
        "Format=\"HDF\">result.h5:/mesh/segments</DataItem>\n",
        num_segments_);
    put("        </Topology>\n        <Geometry GeometryType=\"XYZ\">\n");
    put("          <DataItem Dimensions=\"{} 3\" NumberType=\"Float\" Precision=\"8\" "
        "Format=\"HDF\">{}/centre</DataItem>\n",
        n, at);
    put("        </Geometry>\n");
    put("        <Attribute Name=\"beam\" AttributeType=\"Scalar\" Center=\"Node\">\n"
        "          <DataItem Dimensions=\"{}\" NumberType=\"Int\" Precision=\"8\" "
        "Format=\"HDF\">result.h5:/mesh/node_beam</DataItem>\n        </Attribute>\n",
        n);
    for (const char* vector : {"displacement", "g1", "g2"})
      put("        <Attribute Name=\"{0}\" AttributeType=\"Vector\" Center=\"Node\">\n"
          "          <DataItem Dimensions=\"{1} 3\" NumberType=\"Float\" Precision=\"8\" "
          "Format=\"HDF\">{2}/{0}</DataItem>\n        </Attribute>\n",
          vector, n, at);
    for (int k = 0; k < beam::kNumStrains; ++k)
      put("        <Attribute Name=\"{0}\" AttributeType=\"Scalar\" Center=\"Node\">\n"
          "          <DataItem Dimensions=\"{1}\" NumberType=\"Float\" Precision=\"8\" "
          "Format=\"HDF\">{2}/{0}</DataItem>\n        </Attribute>\n",
          beam::strain_name(k), n, at);
    put("      </Grid>\n");
  }
  put("    </Grid>\n  </Domain>\n</Xdmf>\n");
  write_file_atomically(xdmf_path(), std::string_view(out.data(), out.size()));
}

}  // namespace nodus::output
