#include "nodus/output/hdf5_io.hpp"

#include <algorithm>
#include <mutex>
#include <stdexcept>

#include <fmt/format.h>

namespace nodus::output::hdf5 {

namespace {

/// Datasets of at least this many values are chunked and compressed; smaller ones are stored contiguous
/// (a chunk index and filter costs more than it saves on a few hundred numbers).
constexpr hsize_t kCompressFrom = 1024;
/// Target values per chunk (64 kB of doubles): large enough for deflate, small enough to read a part.
constexpr hsize_t kChunkValues = 8192;

[[noreturn]] void fail(const std::string& what) {
  throw std::runtime_error(what);
}

std::string object_name(hid_t object) {
  const ssize_t n = H5Iget_name(object, nullptr, 0);
  if (n <= 0) return "?";
  std::string name(static_cast<std::size_t>(n), '\0');
  H5Iget_name(object, name.data(), static_cast<std::size_t>(n) + 1);
  return name;
}

std::string file_name(hid_t object) {
  const ssize_t n = H5Fget_name(object, nullptr, 0);
  if (n <= 0) return "?";
  std::string name(static_cast<std::size_t>(n), '\0');
  H5Fget_name(object, name.data(), static_cast<std::size_t>(n) + 1);
  return name;
}

/// "cannot write DATASET in 'FILE'" for a failed call of the writers.
[[noreturn]] void write_failed(hid_t parent, const std::string& name) {
  fail(
      fmt::format("cannot write '{}/{}' in '{}' (HDF5 error)", object_name(parent), name, file_name(parent)));
}

Handle check(hid_t id, hid_t parent, const std::string& name) {
  if (id < 0) write_failed(parent, name);
  return Handle(id);
}

/// A variable-length UTF-8 string type.
Handle string_type() {
  Handle type(H5Tcopy(H5T_C_S1));
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  return type;
}

/// Dataset creation properties for `dims`: chunked, shuffled and deflated when large (`filtered`: numbers;
/// variable-length strings are stored as they are, HDF5 would compress only their references).
Handle creation_properties(const std::vector<hsize_t>& dims, bool filtered) {
  Handle plist(H5Pcreate(H5P_DATASET_CREATE));
  H5Pset_obj_track_times(plist.get(), 0);  // no modification times: the same run gives the same bytes
  hsize_t total = 1;
  for (const hsize_t d : dims) total *= d;
  if (total >= kCompressFrom) {
    if (!filtered || H5Zfilter_avail(H5Z_FILTER_DEFLATE) <= 0) return plist;
    std::vector<hsize_t> chunk = dims;
    const hsize_t row = dims.size() > 1 ? dims[1] : 1;
    chunk[0] = std::max<hsize_t>(1, std::min<hsize_t>(dims[0], kChunkValues / row));
    H5Pset_chunk(plist.get(), static_cast<int>(chunk.size()), chunk.data());
    H5Pset_shuffle(plist.get());
    H5Pset_deflate(plist.get(), 4);
  } else if (total > 0) {
    // Stored in the dataset's object header: no separate block (and its own allocation) per small array.
    H5Pset_layout(plist.get(), H5D_COMPACT);
  }
  return plist;
}

void write_dataset(hid_t parent, const std::string& name, hid_t file_type, hid_t memory_type,
                   const std::vector<hsize_t>& dims, const void* data) {
  remove_link(parent, name);
  Handle space = check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), parent, name);
  Handle plist = creation_properties(dims, H5Tis_variable_str(file_type) <= 0);
  Handle set =
      check(H5Dcreate2(parent, name.c_str(), file_type, space.get(), H5P_DEFAULT, plist.get(), H5P_DEFAULT),
            parent, name);
  if (H5Dwrite(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) write_failed(parent, name);
}

[[noreturn]] void expected(const std::string& file, hid_t parent, const std::string& name,
                           std::string_view what) {
  fail(fmt::format("{}: expected {} at '{}/{}' (a nodus result.h5)", file, what, object_name(parent), name));
}

/// The dataset `name` of `parent` and its dimensions, or an "expected" error.
Handle open_dataset(hid_t parent, const std::string& name, const std::string& file, std::string_view what,
                    std::vector<hsize_t>& dims) {
  if (!has_link(parent, name)) expected(file, parent, name, what);
  Handle set(H5Dopen2(parent, name.c_str(), H5P_DEFAULT));
  if (!set.valid()) expected(file, parent, name, what);
  Handle space(H5Dget_space(set.get()));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) expected(file, parent, name, what);
  dims.assign(static_cast<std::size_t>(rank), 0);
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return set;
}

template <class T>
std::vector<T> read_numbers(hid_t parent, const std::string& name, const std::string& file, hid_t memory_type,
                            H5T_class_t type_class, std::string_view what) {
  std::vector<hsize_t> dims;
  Handle set = open_dataset(parent, name, file, what, dims);
  Handle type(H5Dget_type(set.get()));
  if (dims.size() != 1 || H5Tget_class(type.get()) != type_class) expected(file, parent, name, what);
  std::vector<T> values(static_cast<std::size_t>(dims[0]));
  if (!values.empty() && H5Dread(set.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    expected(file, parent, name, what);
  return values;
}

Handle open_attribute(hid_t object, const std::string& name, const std::string& file, std::string_view what) {
  if (H5Aexists(object, name.c_str()) <= 0)
    fail(fmt::format("{}: expected {} as attribute '{}' of '{}' (a nodus result.h5)", file, what, name,
                     object_name(object)));
  return Handle(H5Aopen(object, name.c_str(), H5P_DEFAULT));
}

void write_attribute(hid_t object, const std::string& name, hid_t file_type, hid_t memory_type,
                     const void* data, hsize_t count = 0, bool scalar = true) {
  if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
  // An empty list has a null dataspace (HDF5 refuses a simple one of size 0 for an attribute).
  Handle space(scalar       ? H5Screate(H5S_SCALAR)
               : count == 0 ? H5Screate(H5S_NULL)
                            : H5Screate_simple(1, &count, nullptr));
  Handle attribute(H5Acreate2(object, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT));
  if (!attribute.valid() || ((scalar || count > 0) && H5Awrite(attribute.get(), memory_type, data) < 0))
    fail(fmt::format("cannot write attribute '{}' of '{}' in '{}' (HDF5 error)", name, object_name(object),
                     file_name(object)));
}

}  // namespace

bool Handle::reset() {
  if (id_ < 0) return true;
  herr_t status = 0;
  switch (H5Iget_type(id_)) {
    case H5I_FILE:
      status = H5Fclose(id_);
      break;
    case H5I_GROUP:
      status = H5Gclose(id_);
      break;
    case H5I_DATASET:
      status = H5Dclose(id_);
      break;
    case H5I_DATASPACE:
      status = H5Sclose(id_);
      break;
    case H5I_DATATYPE:
      status = H5Tclose(id_);
      break;
    case H5I_ATTR:
      status = H5Aclose(id_);
      break;
    case H5I_GENPROP_LST:
      status = H5Pclose(id_);
      break;
    default:
      status = H5Idec_ref(id_);
      break;
  }
  id_ = H5I_INVALID_HID;
  return status >= 0;
}

void silence_errors() {
  static std::once_flag once;
  std::call_once(once, [] {
    // No clean-up at exit: after a write that failed (a full disk) HDF5's own would try to flush the file
    // again and crash; every file nodus opens is closed where it is used.
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  });
}

Handle create_file(const std::filesystem::path& path) {
  silence_errors();
  Handle plist(H5Pcreate(H5P_FILE_CREATE));
  H5Pset_link_creation_order(plist.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
  // Free space tracked in the file, so that the step table rewritten at every state (and the states a resumed
  // run drops) reuse the space they leave instead of growing the file.
  H5Pset_file_space_strategy(plist.get(), H5F_FSPACE_STRATEGY_FSM_AGGR, 1, 1);
  Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, plist.get(), H5P_DEFAULT));
  if (!file.valid()) fail(fmt::format("cannot create '{}' (HDF5 error)", path.string()));
  return file;
}

std::optional<Handle> open_file(const std::filesystem::path& path, bool writable) {
  silence_errors();
  if (H5Fis_hdf5(path.c_str()) <= 0) return std::nullopt;
  Handle file(H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, H5P_DEFAULT));
  if (!file.valid()) return std::nullopt;
  return file;
}

Handle require_group(hid_t parent, const std::string& name) {
  if (has_link(parent, name)) return Handle(H5Gopen2(parent, name.c_str(), H5P_DEFAULT));
  Handle plist(H5Pcreate(H5P_GROUP_CREATE));
  H5Pset_obj_track_times(plist.get(), 0);
  H5Pset_link_creation_order(plist.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED);
  return check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, plist.get(), H5P_DEFAULT), parent, name);
}

Handle open_group(hid_t parent, const std::string& name, std::string_view what) {
  Handle group;
  if (has_link(parent, name)) group = Handle(H5Gopen2(parent, name.c_str(), H5P_DEFAULT));
  if (!group.valid())
    fail(fmt::format("{}: expected {} at '{}/{}' (a nodus result.h5)", file_name(parent), what,
                     object_name(parent), name));
  return group;
}

bool has_link(hid_t parent, const std::string& name) {
  return H5Lexists(parent, name.c_str(), H5P_DEFAULT) > 0;
}

void remove_link(hid_t parent, const std::string& name) {
  if (has_link(parent, name) && H5Ldelete(parent, name.c_str(), H5P_DEFAULT) < 0) write_failed(parent, name);
}

std::vector<std::string> link_names(hid_t group) {
  std::vector<std::string> names;
  H5G_info_t info{};
  if (H5Gget_info(group, &info) < 0) return names;
  // Creation order where the group tracks it (every group nodus writes), else alphabetical.
  Handle plist(H5Gget_create_plist(group));
  unsigned order = 0;
  H5Pget_link_creation_order(plist.get(), &order);
  const H5_index_t index = (order & H5P_CRT_ORDER_TRACKED) ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t n = H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    if (n < 0) continue;
    std::string name(static_cast<std::size_t>(n), '\0');
    H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, k, name.data(), static_cast<std::size_t>(n) + 1,
                       H5P_DEFAULT);
    names.push_back(name);
  }
  return names;
}

void write_doubles(hid_t parent, const std::string& name, const std::vector<double>& values) {
  write_dataset(parent, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {values.size()}, values.data());
}

void write_ints(hid_t parent, const std::string& name, const std::vector<std::int64_t>& values) {
  write_dataset(parent, name, H5T_STD_I64LE, H5T_NATIVE_INT64, {values.size()}, values.data());
}

void write_strings(hid_t parent, const std::string& name, const std::vector<std::string>& values) {
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const std::string& v : values) pointers.push_back(v.c_str());
  Handle type = string_type();
  write_dataset(parent, name, type.get(), type.get(), {values.size()}, pointers.data());
}

void write_matrix(hid_t parent, const std::string& name, const std::vector<double>& values, int columns) {
  const auto c = static_cast<hsize_t>(columns);
  write_dataset(parent, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {values.size() / c, c}, values.data());
}

void write_int_matrix(hid_t parent, const std::string& name, const std::vector<std::int64_t>& values,
                      int columns) {
  const auto c = static_cast<hsize_t>(columns);
  write_dataset(parent, name, H5T_STD_I64LE, H5T_NATIVE_INT64, {values.size() / c, c}, values.data());
}

void write_text(hid_t parent, const std::string& name, const std::string& text) {
  remove_link(parent, name);
  Handle type = string_type();
  Handle space(H5Screate(H5S_SCALAR));
  Handle set =
      check(H5Dcreate2(parent, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
            parent, name);
  const char* pointer = text.c_str();
  if (H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &pointer) < 0)
    write_failed(parent, name);
}

void set_attribute(hid_t object, const std::string& name, const std::string& value) {
  Handle type = string_type();
  const char* pointer = value.c_str();
  write_attribute(object, name, type.get(), type.get(), &pointer);
}

void set_attribute(hid_t object, const std::string& name, double value) {
  write_attribute(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void set_attribute(hid_t object, const std::string& name, std::int64_t value) {
  write_attribute(object, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

void set_attribute(hid_t object, const std::string& name, const std::vector<std::string>& values) {
  std::vector<const char*> pointers;
  for (const std::string& v : values) pointers.push_back(v.c_str());
  Handle type = string_type();
  write_attribute(object, name, type.get(), type.get(), pointers.data(), values.size(), false);
}

std::vector<double> read_doubles(hid_t parent, const std::string& name, const std::string& file) {
  return read_numbers<double>(parent, name, file, H5T_NATIVE_DOUBLE, H5T_FLOAT, "a 1-D float64 dataset");
}

std::vector<std::int64_t> read_ints(hid_t parent, const std::string& name, const std::string& file) {
  return read_numbers<std::int64_t>(parent, name, file, H5T_NATIVE_INT64, H5T_INTEGER,
                                    "a 1-D integer dataset");
}

std::vector<std::string> read_strings(hid_t parent, const std::string& name, const std::string& file) {
  constexpr std::string_view what = "a 1-D string dataset";
  std::vector<hsize_t> dims;
  Handle set = open_dataset(parent, name, file, what, dims);
  Handle file_type(H5Dget_type(set.get()));
  if (dims.size() != 1 || H5Tget_class(file_type.get()) != H5T_STRING || !H5Tis_variable_str(file_type.get()))
    expected(file, parent, name, what);
  std::vector<char*> pointers(static_cast<std::size_t>(dims[0]), nullptr);
  std::vector<std::string> values;
  if (pointers.empty()) return values;
  Handle type = string_type();
  if (H5Dread(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()) < 0)
    expected(file, parent, name, what);
  for (char* p : pointers) values.emplace_back(p ? p : "");
  Handle space(H5Dget_space(set.get()));
  H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, pointers.data());
  return values;
}

std::vector<std::array<double, 3>> read_points(hid_t parent, const std::string& name,
                                               const std::string& file) {
  constexpr std::string_view what = "an N x 3 float64 dataset";
  std::vector<hsize_t> dims;
  Handle set = open_dataset(parent, name, file, what, dims);
  Handle type(H5Dget_type(set.get()));
  if (dims.size() != 2 || dims[1] != 3 || H5Tget_class(type.get()) != H5T_FLOAT)
    expected(file, parent, name, what);
  std::vector<std::array<double, 3>> points(static_cast<std::size_t>(dims[0]));
  if (!points.empty() &&
      H5Dread(set.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, points.data()) < 0)
    expected(file, parent, name, what);
  return points;
}

std::string read_text(hid_t parent, const std::string& name, const std::string& file) {
  constexpr std::string_view what = "a string";
  std::vector<hsize_t> dims;
  Handle set = open_dataset(parent, name, file, what, dims);
  Handle file_type(H5Dget_type(set.get()));
  if (!dims.empty() || H5Tget_class(file_type.get()) != H5T_STRING || !H5Tis_variable_str(file_type.get()))
    expected(file, parent, name, what);
  Handle type = string_type();
  char* pointer = nullptr;
  if (H5Dread(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, &pointer) < 0)
    expected(file, parent, name, what);
  std::string text = pointer ? pointer : "";
  Handle space(H5Dget_space(set.get()));
  H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, &pointer);
  return text;
}

std::string string_attribute(hid_t object, const std::string& name, const std::string& file) {
  Handle attribute = open_attribute(object, name, file, "a string");
  Handle file_type(H5Aget_type(attribute.get()));
  Handle type = string_type();
  char* pointer = nullptr;
  if (H5Tget_class(file_type.get()) != H5T_STRING || !H5Tis_variable_str(file_type.get()) ||
      H5Aread(attribute.get(), type.get(), &pointer) < 0)
    fail(fmt::format("{}: expected a string as attribute '{}' of '{}'", file, name, object_name(object)));
  std::string value = pointer ? pointer : "";
  Handle space(H5Aget_space(attribute.get()));
  H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, &pointer);
  return value;
}

double double_attribute(hid_t object, const std::string& name, const std::string& file) {
  Handle attribute = open_attribute(object, name, file, "a number");
  double value = 0.0;
  if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value) < 0)
    fail(fmt::format("{}: expected a number as attribute '{}' of '{}'", file, name, object_name(object)));
  return value;
}

std::int64_t int_attribute(hid_t object, const std::string& name, const std::string& file) {
  Handle attribute = open_attribute(object, name, file, "an integer");
  Handle type(H5Aget_type(attribute.get()));
  std::int64_t value = 0;
  if (H5Tget_class(type.get()) != H5T_INTEGER || H5Aread(attribute.get(), H5T_NATIVE_INT64, &value) < 0)
    fail(fmt::format("{}: expected an integer as attribute '{}' of '{}'", file, name, object_name(object)));
  return value;
}

}  // namespace nodus::output::hdf5
