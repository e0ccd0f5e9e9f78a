#pragma once
/// A thin layer over the HDF5 C library for result.h5 (result_h5.hpp): handles that close themselves, and
/// one-dimensional and N x 3 datasets and scalar attributes of the few types the file holds (float64, int64,
/// UTF-8 strings). Every failure throws std::runtime_error naming the file and the object, and HDF5's own
/// error stack is not printed (the messages say what matters in one line).

#include <hdf5.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace nodus::output::hdf5 {

/// An HDF5 identifier closed with the function that fits its kind when the handle goes.
class Handle {
 public:
  Handle() = default;
  explicit Handle(hid_t id) : id_(id) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept : id_(other.id_) { other.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = other.id_;
      other.id_ = H5I_INVALID_HID;
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Closes it now; returns false if HDF5 reported an error (for a file: its data could not be flushed).
  bool reset();

 private:
  hid_t id_ = H5I_INVALID_HID;
};

/// Turns off HDF5's printing of its error stack on stderr (once per process).
void silence_errors();

/// Creates (truncating) the file at `path`, links tracked in creation order. Throws on failure.
Handle create_file(const std::filesystem::path& path);
/// Opens the file at `path` for reading (`writable` false) or writing; nullopt if HDF5 cannot open it (not
/// an HDF5 file, or one damaged).
std::optional<Handle> open_file(const std::filesystem::path& path, bool writable);

/// The group `name` under `parent`, created (links in creation order) if missing.
Handle require_group(hid_t parent, const std::string& name);
/// The group `name` under `parent`; throws naming `what` if it is missing.
Handle open_group(hid_t parent, const std::string& name, std::string_view what);
/// Whether `parent` has a link called `name` (one path component).
bool has_link(hid_t parent, const std::string& name);
/// Removes link `name` from `parent` if it is there.
void remove_link(hid_t parent, const std::string& name);
/// The names of the links of `group`, in creation order where it is tracked, else by name.
std::vector<std::string> link_names(hid_t group);

/// 1-D datasets; replace one of the same name. Large ones are chunked and compressed (deflate + shuffle).
void write_doubles(hid_t parent, const std::string& name, const std::vector<double>& values);
void write_ints(hid_t parent, const std::string& name, const std::vector<std::int64_t>& values);
void write_strings(hid_t parent, const std::string& name, const std::vector<std::string>& values);
/// An n x `columns` dataset of doubles or ints from row-major `values` (n = size / columns).
void write_matrix(hid_t parent, const std::string& name, const std::vector<double>& values, int columns);
void write_int_matrix(hid_t parent, const std::string& name, const std::vector<std::int64_t>& values,
                      int columns);
/// A scalar string dataset (a text such as the scenario echo).
void write_text(hid_t parent, const std::string& name, const std::string& text);

/// Scalar attributes of an object; replace one of the same name.
void set_attribute(hid_t object, const std::string& name, const std::string& value);
void set_attribute(hid_t object, const std::string& name, double value);
void set_attribute(hid_t object, const std::string& name, std::int64_t value);
/// A 1-D string attribute.
void set_attribute(hid_t object, const std::string& name, const std::vector<std::string>& values);

/// Readers: throw a one-line std::runtime_error naming `file` and what was expected when the object is
/// missing or of another shape or type.
std::vector<double> read_doubles(hid_t parent, const std::string& name, const std::string& file);
std::vector<std::int64_t> read_ints(hid_t parent, const std::string& name, const std::string& file);
std::vector<std::string> read_strings(hid_t parent, const std::string& name, const std::string& file);
/// An n x 3 float64 dataset as n points.
std::vector<std::array<double, 3>> read_points(hid_t parent, const std::string& name,
                                               const std::string& file);
std::string read_text(hid_t parent, const std::string& name, const std::string& file);
std::string string_attribute(hid_t object, const std::string& name, const std::string& file);
double double_attribute(hid_t object, const std::string& name, const std::string& file);
std::int64_t int_attribute(hid_t object, const std::string& name, const std::string& file);

}  // namespace nodus::output::hdf5
