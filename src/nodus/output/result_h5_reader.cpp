// Reading result.h5 back (read_result_h5), and its canonical text (result_h5_text): see result_h5.hpp.

#include <algorithm>
#include <map>
#include <stdexcept>

#include <fmt/format.h>

#include "nodus/beam/strain_measures.hpp"
#include "nodus/output/hdf5_io.hpp"
#include "nodus/output/result_h5.hpp"

namespace nodus::output {

namespace {

using hdf5::Handle;

[[noreturn]] void fail(const std::string& file, const std::string& what) {
  throw std::runtime_error(fmt::format("{}: expected {}", file, what));
}

template <class T>
void check_size(const std::vector<T>& values, std::size_t n, const std::string& file,
                const std::string& what) {
  if (values.size() != n) fail(file, fmt::format("{} of {} values, got {}", what, n, values.size()));
}

std::vector<int> to_int(const std::vector<std::int64_t>& values) {
  return std::vector<int>(values.begin(), values.end());
}

/// The contact elements of a state's `contact` group.
ResultContacts read_contacts(hid_t group, const std::string& file) {
  ResultContacts c;
  const std::vector<std::int64_t> zone = hdf5::read_ints(group, "zone", file);
  const std::size_t n = zone.size();
  c.zone = to_int(zone);
  c.beam_i = to_int(hdf5::read_ints(group, "beam_i", file));
  c.beam_j = to_int(hdf5::read_ints(group, "beam_j", file));
  check_size(c.beam_i, n, file, "contact/beam_i");
  check_size(c.beam_j, n, file, "contact/beam_j");
  auto points = [&](const char* x, const char* y, const char* z) {
    const std::vector<double> vx = hdf5::read_doubles(group, x, file);
    const std::vector<double> vy = hdf5::read_doubles(group, y, file);
    const std::vector<double> vz = hdf5::read_doubles(group, z, file);
    check_size(vx, n, file, std::string("contact/") + x);
    check_size(vy, n, file, std::string("contact/") + y);
    check_size(vz, n, file, std::string("contact/") + z);
    std::vector<std::array<double, 3>> p(n);
    for (std::size_t k = 0; k < n; ++k) p[k] = {vx[k], vy[k], vz[k]};
    return p;
  };
  c.x_i = points("x_i", "y_i", "z_i");
  c.x_j = points("x_j", "y_j", "z_j");
  c.normal = points("nx", "ny", "nz");
  c.gap = hdf5::read_doubles(group, "gap", file);
  check_size(c.gap, n, file, "contact/gap");
  if (hdf5::has_link(group, "normal_force")) {  // a state with contact forces
    c.normal_force = hdf5::read_doubles(group, "normal_force", file);
    c.tangential_force = hdf5::read_doubles(group, "tangential_force", file);
    c.state = hdf5::read_strings(group, "state", file);
    check_size(c.normal_force, n, file, "contact/normal_force");
    check_size(c.tangential_force, n, file, "contact/tangential_force");
    check_size(c.state, n, file, "contact/state");
  }
  return c;
}

ResultState read_state(hid_t group, const std::string& file, std::size_t num_nodes) {
  ResultState s;
  s.step = static_cast<int>(hdf5::int_attribute(group, "step", file));
  s.load_time = hdf5::double_attribute(group, "load_time", file);
  s.stage = hdf5::string_attribute(group, "stage", file);
  s.centre = hdf5::read_points(group, "centre", file);
  s.g1 = hdf5::read_points(group, "g1", file);
  s.g2 = hdf5::read_points(group, "g2", file);
  check_size(s.centre, num_nodes, file, fmt::format("state {}: centre", s.step));
  check_size(s.g1, num_nodes, file, fmt::format("state {}: g1", s.step));
  check_size(s.g2, num_nodes, file, fmt::format("state {}: g2", s.step));
  for (int k = 0; k < beam::kNumStrains; ++k) {
    std::vector<double> values = hdf5::read_doubles(group, beam::strain_name(k), file);
    check_size(values, num_nodes, file, fmt::format("state {}: {}", s.step, beam::strain_name(k)));
    s.node_fields.emplace(beam::strain_name(k), std::move(values));
  }
  if (hdf5::has_link(group, "contact")) {
    Handle contact = hdf5::open_group(group, "contact", "the contact elements");
    s.contacts = read_contacts(contact.get(), file);
  }
  return s;
}

ResultRun read_run(const std::filesystem::path& run_dir) {
  const std::filesystem::path path = run_dir / "result.h5";
  const std::string file = path.string();
  if (!std::filesystem::exists(path)) fail(file, "a nodus result file (result.h5), got none");
  std::optional<Handle> opened = hdf5::open_file(path, false);
  if (!opened) fail(file, "an HDF5 file (a nodus result.h5), got one HDF5 cannot open");
  const hid_t root = opened->get();
  if (H5Aexists(root, "format") <= 0 || hdf5::string_attribute(root, "format", file) != kResultFormat)
    fail(file, fmt::format("a nodus result (root attribute format = '{}')", kResultFormat));
  const std::int64_t version = hdf5::int_attribute(root, "format_version", file);
  if (version != kResultFormatVersion)
    fail(file, fmt::format("format_version {}, got {}", kResultFormatVersion, version));

  ResultRun run;
  run.name = hdf5::string_attribute(root, "run", file);
  {
    Handle beams = hdf5::open_group(root, "beams", "the beams");
    const std::vector<std::string> names = hdf5::read_strings(beams.get(), "name", file);
    const std::vector<double> radius = hdf5::read_doubles(beams.get(), "radius", file);
    const std::vector<double> young = hdf5::read_doubles(beams.get(), "young_modulus", file);
    const std::vector<std::int64_t> first = hdf5::read_ints(beams.get(), "first_node", file);
    const std::vector<std::int64_t> count = hdf5::read_ints(beams.get(), "node_count", file);
    const std::vector<std::int64_t> tool = hdf5::read_ints(beams.get(), "tool", file);
    const std::size_t n = names.size();
    check_size(radius, n, file, "beams/radius");
    check_size(young, n, file, "beams/young_modulus");
    check_size(first, n, file, "beams/first_node");
    check_size(count, n, file, "beams/node_count");
    check_size(tool, n, file, "beams/tool");
    for (std::size_t b = 0; b < n; ++b)
      run.beams.push_back({names[b], radius[b], young[b], static_cast<int>(first[b]),
                           static_cast<int>(count[b]), tool[b] != 0});
  }
  std::size_t num_nodes = 0;
  for (const ResultBeam& b : run.beams) num_nodes += static_cast<std::size_t>(b.node_count);
  {
    Handle stages = hdf5::open_group(root, "stages", "the stages");
    const std::vector<std::string> names = hdf5::read_strings(stages.get(), "name", file);
    const std::vector<double> start = hdf5::read_doubles(stages.get(), "start_time", file);
    const std::vector<double> end = hdf5::read_doubles(stages.get(), "end_time", file);
    check_size(start, names.size(), file, "stages/start_time");
    check_size(end, names.size(), file, "stages/end_time");
    for (std::size_t k = 0; k < names.size(); ++k) run.stages.push_back({names[k], start[k], end[k]});
  }
  {
    Handle states = hdf5::open_group(root, "states", "the output states");
    for (const std::string& name : hdf5::link_names(states.get())) {
      Handle state = hdf5::open_group(states.get(), name, "an output state");
      run.states.push_back(read_state(state.get(), file, num_nodes));
    }
    std::stable_sort(run.states.begin(), run.states.end(),
                     [](const ResultState& a, const ResultState& b) { return a.step < b.step; });
  }
  if (hdf5::has_link(root, "branches")) {
    Handle branches = hdf5::open_group(root, "branches", "the branches");
    for (const std::string& name : hdf5::link_names(branches.get())) {
      // An external link to branches/NAME/result.h5: read it as a run of its own, if the branch ran.
      const std::filesystem::path dir = run_dir / "branches" / name;
      if (!std::filesystem::exists(dir / "result.h5")) continue;
      run.branches.push_back(read_run(dir));
    }
  }
  return run;
}

/// One line per dataset and attribute under `object` (a group), recursively, in name order.
void describe(hid_t object, const std::string& at, const std::set<std::string>& skipped, std::string& out) {
  auto values_text = [](hid_t item, bool attribute) -> std::string {
    Handle type(attribute ? H5Aget_type(item) : H5Dget_type(item));
    Handle space(attribute ? H5Aget_space(item) : H5Dget_space(item));
    const hssize_t n = H5Sget_simple_extent_npoints(space.get());
    const int rank = H5Sget_simple_extent_ndims(space.get());
    std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
    if (rank > 0) H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
    std::string text = "[";
    for (std::size_t k = 0; k < dims.size(); ++k) text += (k ? "x" : "") + std::to_string(dims[k]);
    text += "] ";
    const H5T_class_t type_class = H5Tget_class(type.get());
    auto read = [&](hid_t memory_type, void* buffer) {
      return attribute ? H5Aread(item, memory_type, buffer)
                       : H5Dread(item, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer);
    };
    if (n <= 0) return text;
    if (type_class == H5T_FLOAT) {
      std::vector<double> v(static_cast<std::size_t>(n));
      read(H5T_NATIVE_DOUBLE, v.data());
      for (const double x : v) text += fmt::format("{:.17g} ", x);
    } else if (type_class == H5T_INTEGER) {
      std::vector<std::int64_t> v(static_cast<std::size_t>(n));
      read(H5T_NATIVE_INT64, v.data());
      for (const std::int64_t x : v) text += fmt::format("{} ", x);
    } else if (type_class == H5T_STRING && H5Tis_variable_str(type.get()) > 0) {
      Handle memory(H5Tcopy(H5T_C_S1));
      H5Tset_size(memory.get(), H5T_VARIABLE);
      H5Tset_cset(memory.get(), H5T_CSET_UTF8);
      std::vector<char*> v(static_cast<std::size_t>(n), nullptr);
      read(memory.get(), v.data());
      for (char* p : v) text += fmt::format("'{}' ", p ? p : "");
      H5Dvlen_reclaim(memory.get(), space.get(), H5P_DEFAULT, v.data());
    } else {
      text += "(other type)";
    }
    return text;
  };
  // Attributes of the object, by name.
  std::vector<std::string> attributes;
  H5O_info_t info{};
  H5Oget_info2(object, &info, H5O_INFO_NUM_ATTRS);
  for (hsize_t k = 0; k < info.num_attrs; ++k) {
    const ssize_t n = H5Aget_name_by_idx(object, ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    std::string name(static_cast<std::size_t>(std::max<ssize_t>(n, 0)), '\0');
    H5Aget_name_by_idx(object, ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), name.size() + 1, H5P_DEFAULT);
    attributes.push_back(name);
  }
  std::sort(attributes.begin(), attributes.end());
  for (const std::string& name : attributes) {
    if (skipped.contains(name)) continue;
    Handle attribute(H5Aopen(object, name.c_str(), H5P_DEFAULT));
    out += at + "@" + name + " " + values_text(attribute.get(), true) + "\n";
  }
  if (H5Iget_type(object) != H5I_GROUP) return;
  std::vector<std::string> names;
  H5G_info_t group{};
  H5Gget_info(object, &group);
  for (hsize_t k = 0; k < group.nlinks; ++k) {
    const ssize_t n = H5Lget_name_by_idx(object, ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    std::string name(static_cast<std::size_t>(std::max<ssize_t>(n, 0)), '\0');
    H5Lget_name_by_idx(object, ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), name.size() + 1, H5P_DEFAULT);
    names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  for (const std::string& name : names) {
    const std::string path = at + "/" + name;
    H5L_info_t link{};
    H5Lget_info(object, name.c_str(), &link, H5P_DEFAULT);
    if (link.type == H5L_TYPE_EXTERNAL) {
      std::vector<char> value(link.u.val_size);
      H5Lget_val(object, name.c_str(), value.data(), value.size(), H5P_DEFAULT);
      const char* target_file = nullptr;
      const char* target_object = nullptr;
      H5Lunpack_elink_val(value.data(), value.size(), nullptr, &target_file, &target_object);
      out += fmt::format("{} -> {}:{}\n", path, target_file ? target_file : "",
                         target_object ? target_object : "");
      continue;
    }
    Handle child(H5Oopen(object, name.c_str(), H5P_DEFAULT));
    if (H5Iget_type(child.get()) == H5I_DATASET) {
      out += path + " " + values_text(child.get(), false) + "\n";
      describe(child.get(), path, skipped, out);  // its attributes
    } else {
      out += path + "/\n";
      describe(child.get(), path, skipped, out);
    }
  }
}

}  // namespace

ResultRun read_result_h5(const std::filesystem::path& run_dir) {
  hdf5::silence_errors();
  return read_run(run_dir);
}

std::string result_h5_text(const std::filesystem::path& path, const std::set<std::string>& skipped) {
  std::optional<Handle> file = hdf5::open_file(path, false);
  if (!file)
    throw std::runtime_error(
        fmt::format("{}: expected an HDF5 file, got one HDF5 cannot open", path.string()));
  std::string out;
  Handle root(H5Gopen2(file->get(), "/", H5P_DEFAULT));
  describe(root.get(), "", skipped, out);
  return out;
}

}  // namespace nodus::output
