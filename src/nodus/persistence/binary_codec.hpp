#pragma once
/// The binary encoding of nodus's state files: integers little-endian, doubles as their IEEE 754 bits
/// little-endian, a string or list as a u64 count followed by its items. A Decoder that runs past the end, or
/// meets a value out of range, reports a damaged file (scenario::ScenarioError, one line).

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include <Eigen/Core>

namespace nodus::persistence {

/// Throws scenario::ScenarioError "PATH: checkpoint: expected EXPECTED, got GOT" (a foreign file: another
/// format version, another scenario).
[[noreturn]] void bad_file(const std::filesystem::path& path, std::string_view expected,
                           std::string_view got);
/// Throws DamagedFile (a scenario::ScenarioError) with bad_file's message: a file cut short, changed after
/// it was written (its checksum), or not a state file at all.
[[noreturn]] void damaged_file(const std::filesystem::path& path, std::string_view expected,
                               std::string_view got);

/// Appends values in the file's byte order.
class Encoder {
 public:
  void u8(std::uint8_t v) { out_.push_back(static_cast<char>(v)); }
  void u32(std::uint32_t v) {
    for (int k = 0; k < 4; ++k) u8(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  void u64(std::uint64_t v) {
    for (int k = 0; k < 8; ++k) u8(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  void i32(int v) { u32(static_cast<std::uint32_t>(v)); }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void boolean(bool v) { u8(v ? 1 : 0); }
  void count(std::size_t n) { u64(static_cast<std::uint64_t>(n)); }
  void text(std::string_view s) {
    count(s.size());
    out_.append(s);
  }
  template <class Derived>
  void matrix(const Eigen::MatrixBase<Derived>& m) {  // fixed size: the values only
    for (Eigen::Index i = 0; i < m.size(); ++i) f64(m(i));
  }
  void vector(const Eigen::VectorXd& v) {
    count(static_cast<std::size_t>(v.size()));
    matrix(v);
  }
  void raw(std::string_view bytes) { out_.append(bytes); }
  const std::string& bytes() const { return out_; }

 private:
  std::string out_;
};

/// Reads values in the file's byte order; running past the end means a damaged file.
class Decoder {
 public:
  Decoder(std::string_view bytes, const std::filesystem::path& path) : bytes_(bytes), path_(path) {}

  std::uint8_t u8() {
    need(1);
    return static_cast<std::uint8_t>(bytes_[pos_++]);
  }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= static_cast<std::uint32_t>(u8()) << (8 * k);
    return v;
  }
  std::uint64_t u64() {
    std::uint64_t v = 0;
    for (int k = 0; k < 8; ++k) v |= static_cast<std::uint64_t>(u8()) << (8 * k);
    return v;
  }
  int i32() { return static_cast<int>(u32()); }
  double f64() { return std::bit_cast<double>(u64()); }
  bool boolean() {
    const std::uint8_t v = u8();
    if (v > 1) damaged();
    return v == 1;
  }
  /// A count of items of at least `item_bytes` bytes each.
  std::size_t count(std::size_t item_bytes) {
    const std::uint64_t n = u64();
    if (n > (bytes_.size() - pos_) / std::max<std::size_t>(item_bytes, 1)) damaged();
    return static_cast<std::size_t>(n);
  }
  std::string text() {
    const std::size_t n = count(1);
    std::string s(bytes_.substr(pos_, n));
    pos_ += n;
    return s;
  }
  template <class Fixed>
  Fixed matrix() {
    Fixed m;
    for (Eigen::Index i = 0; i < m.size(); ++i) m(i) = f64();
    return m;
  }
  Eigen::VectorXd vector() {
    Eigen::VectorXd v(static_cast<Eigen::Index>(count(8)));
    for (Eigen::Index i = 0; i < v.size(); ++i) v[i] = f64();
    return v;
  }
  std::size_t position() const { return pos_; }
  [[noreturn]] void damaged() const {
    damaged_file(path_, "a complete checkpoint", "a damaged or truncated file");
  }

 private:
  void need(std::size_t n) const {
    if (bytes_.size() - pos_ < n) damaged();
  }
  std::string_view bytes_;
  std::size_t pos_ = 0;
  const std::filesystem::path& path_;
};

}  // namespace nodus::persistence
