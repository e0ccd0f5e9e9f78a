#pragma once
// Shared helpers of the output tests: a scratch folder, a small two-beam model, a deformed state, a minimal
// XML reader that checks well-formedness (balanced tags, quoted attributes), and a reader of VTK files that
// decodes their compressed appended arrays from the format's description (VTK's file-formats page), not from
// nodus's writer.

#include <gtest/gtest.h>

#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>
#include <zlib.h>

#include <Eigen/Core>

#include "nodus/beam/beam.hpp"
#include "nodus/model/model.hpp"

namespace nodus::output::testing {

/// A fresh, empty folder under the system temporary folder, named after the running test; removed afterwards.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() / ("nodus_output_" + std::string(info->test_suite_name()) +
                                                      "_" + info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Beam "a" along x (2 elements, R = 0.5 mm) and beam "b" along z from (1, 2, 3) (1 element, R = 0.25 mm).
inline model::Model two_beam_model() {
  model::Model m;
  m.add_beam(beam::BeamDefinition{"a", 10.0, 0.5, 2, beam::Vec3::Zero(), beam::Vec3::UnitX(),
                                  beam::Vec3::UnitY(), beam::ElasticConstants{1000.0, 0.3}, 1.0});
  m.add_beam(beam::BeamDefinition{"b", 4.0, 0.25, 1, beam::Vec3(1, 2, 3), beam::Vec3::UnitZ(),
                                  beam::Vec3::UnitX(), beam::ElasticConstants{1000.0, 0.3}, 1.0});
  return m;
}

/// The reference state with a smooth, non-rigid perturbation of every unknown (sections stretched and
/// sheared).
inline Eigen::VectorXd deformed_state(const model::Model& m) {
  Eigen::VectorXd x = m.reference();
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] += 0.05 * std::sin(0.7 * static_cast<double>(i) + 0.3);
  return x;
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator && separator != '\n') parts.emplace_back();
  return parts;
}

/// The records of a CSV text (RFC 4180): fields separated by commas, records by line ends outside double
/// quotes; a quoted field holds commas, line ends and doubled quotes (one quote each). The records of
/// `text`'s lines, the last line end optional.
inline std::vector<std::vector<std::string>> csv_records(const std::string& text) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c != '"')
        field += c;
      else if (i + 1 < text.size() && text[i + 1] == '"')
        field += text[++i];
      else
        quoted = false;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      record.push_back(field);
      field.clear();
    } else if (c == '\n') {
      record.push_back(field);
      field.clear();
      records.push_back(record);
      record.clear();
    } else {
      field += c;
    }
  }
  if (!field.empty() || !record.empty()) {
    record.push_back(field);
    records.push_back(record);
  }
  return records;
}

inline std::vector<double> numbers(const std::string& text) {
  std::vector<double> values;
  std::istringstream in(text);
  double v;
  while (in >> v) values.push_back(v);
  if (!in.eof()) throw std::runtime_error("not a number list: " + text.substr(0, 80));
  return values;
}

/// An element of a parsed XML document.
struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;  ///< character data directly inside the element
  std::vector<std::unique_ptr<XmlElement>> children;

  const std::string& attribute(const std::string& key) const {
    const auto it = attributes.find(key);
    if (it == attributes.end()) throw std::runtime_error("<" + name + "> has no attribute " + key);
    return it->second;
  }
  std::vector<const XmlElement*> all(const std::string& child) const {
    std::vector<const XmlElement*> found;
    for (const auto& c : children)
      if (c->name == child) found.push_back(c.get());
    return found;
  }
  const XmlElement& one(const std::string& child) const {
    const auto found = all(child);
    if (found.size() != 1)
      throw std::runtime_error("<" + name + "> has " + std::to_string(found.size()) + " <" + child + ">");
    return *found.front();
  }
  /// The child DataArray with Name = `array_name`.
  const XmlElement& data_array(const std::string& array_name) const {
    for (const XmlElement* a : all("DataArray"))
      if (a->attributes.count("Name") && a->attributes.at("Name") == array_name) return *a;
    throw std::runtime_error("<" + name + "> has no DataArray " + array_name);
  }
};

/// Parses a document without DTD, comments or CDATA (what our writers produce); throws std::runtime_error on
/// unbalanced or malformed tags.
inline std::unique_ptr<XmlElement> parse_xml(const std::string& doc) {
  std::size_t pos = 0;
  auto fail = [&](const std::string& why) {
    throw std::runtime_error("XML at " + std::to_string(pos) + ": " + why);
  };
  std::unique_ptr<XmlElement> root;
  std::vector<XmlElement*> open;
  while (pos < doc.size()) {
    const std::size_t lt = doc.find('<', pos);
    const std::string text = doc.substr(pos, lt == std::string::npos ? std::string::npos : lt - pos);
    if (open.empty()) {
      for (char c : text)
        if (!std::isspace(static_cast<unsigned char>(c))) fail("text outside the root element");
    } else {
      open.back()->text += text;
    }
    if (lt == std::string::npos) break;
    const std::size_t gt = doc.find('>', lt);
    if (gt == std::string::npos) fail("unterminated tag");
    std::string tag = doc.substr(lt + 1, gt - lt - 1);
    pos = gt + 1;
    if (!tag.empty() && tag.front() == '?') {
      if (tag.back() != '?' || root) fail("bad processing instruction");
      continue;
    }
    if (!tag.empty() && tag.front() == '/') {
      if (open.empty() || open.back()->name != tag.substr(1)) fail("unbalanced </" + tag.substr(1) + ">");
      open.pop_back();
      continue;
    }
    const bool self_closing = !tag.empty() && tag.back() == '/';
    if (self_closing) tag.pop_back();
    auto element = std::make_unique<XmlElement>();
    std::size_t i = 0;
    while (i < tag.size() && !std::isspace(static_cast<unsigned char>(tag[i]))) element->name += tag[i++];
    if (element->name.empty()) fail("empty tag name");
    while (true) {
      while (i < tag.size() && std::isspace(static_cast<unsigned char>(tag[i]))) ++i;
      if (i >= tag.size()) break;
      const std::size_t eq = tag.find('=', i);
      if (eq == std::string::npos || eq + 1 >= tag.size() || tag[eq + 1] != '"')
        fail("bad attribute in <" + tag + ">");
      const std::size_t close = tag.find('"', eq + 2);
      if (close == std::string::npos) fail("unterminated attribute value");
      const std::string key = tag.substr(i, eq - i);
      if (!element->attributes.emplace(key, tag.substr(eq + 2, close - eq - 2)).second)
        fail("duplicate " + key);
      i = close + 1;
    }
    XmlElement* raw = element.get();
    if (open.empty()) {
      if (root) fail("second root element");
      root = std::move(element);
    } else {
      open.back()->children.push_back(std::move(element));
    }
    if (!self_closing) open.push_back(raw);
  }
  if (!open.empty()) fail("unclosed <" + open.back()->name + ">");
  if (!root) fail("no root element");
  return root;
}

/// The values of one appended array of a VTK file with header_type="UInt64" and the zlib compressor:
/// `data` points at its header [blocks, block size, last block size or 0, compressed sizes], then the
/// compressed blocks. The bytes are read as `T`, little-endian (the test machines' order).
template <typename T>
std::vector<double> decode_appended(const std::string& appended, std::size_t offset) {
  auto word = [&](std::size_t i) {
    std::uint64_t w = 0;
    if (offset + 8 * (i + 1) > appended.size()) throw std::runtime_error("appended header out of the data");
    std::memcpy(&w, appended.data() + offset + 8 * i, 8);
    return w;
  };
  const std::uint64_t blocks = word(0), block_size = word(1), last_size = word(2);
  std::string bytes;
  std::size_t at = offset + 8 * (3 + blocks);
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const std::uint64_t compressed = word(3 + b);
    uLongf size = static_cast<uLongf>(b + 1 == blocks && last_size != 0 ? last_size : block_size);
    std::string block(size, '\0');
    if (at + compressed > appended.size() ||
        uncompress(reinterpret_cast<Bytef*>(block.data()), &size,
                   reinterpret_cast<const Bytef*>(appended.data() + at),
                   static_cast<uLong>(compressed)) != Z_OK ||
        size != block.size())
      throw std::runtime_error("appended block " + std::to_string(b) + " does not uncompress to its size");
    bytes += block;
    at += compressed;
  }
  if (bytes.size() % sizeof(T) != 0)
    throw std::runtime_error("appended array is not a whole number of values");
  std::vector<double> values(bytes.size() / sizeof(T));
  for (std::size_t i = 0; i < values.size(); ++i) {
    T v;
    std::memcpy(&v, bytes.data() + i * sizeof(T), sizeof(T));
    values[i] = static_cast<double>(v);
  }
  return values;
}

/// Parses a VTK XML document, ASCII or with raw appended data: in the latter, every DataArray of
/// format="appended" gets as its text the decoded values (17 significant digits), so that a test reads both
/// encodings alike. Throws std::runtime_error on a malformed document or array.
inline std::unique_ptr<XmlElement> parse_vtk(const std::string& doc) {
  const std::string opening = "<AppendedData encoding=\"raw\">";
  const std::size_t start = doc.find(opening);
  if (start == std::string::npos) return parse_xml(doc);
  const std::size_t underscore = doc.find('_', start + opening.size());
  const std::string closing = "</AppendedData>";
  const std::size_t end = doc.rfind(closing);
  if (underscore == std::string::npos || end == std::string::npos || end < underscore)
    throw std::runtime_error("AppendedData without '_' or its closing tag");
  const std::string appended = doc.substr(underscore + 1, end - underscore - 1);
  auto root = parse_xml(doc.substr(0, start) + doc.substr(end + closing.size()));
  if (root->attribute("header_type") != "UInt64" || root->attribute("compressor") != "vtkZLibDataCompressor")
    throw std::runtime_error("expected header_type UInt64 and the zlib compressor");
  std::vector<XmlElement*> stack{root.get()};
  while (!stack.empty()) {
    XmlElement* e = stack.back();
    stack.pop_back();
    for (auto& c : e->children) stack.push_back(c.get());
    if (e->name != "DataArray" || !e->attributes.count("format") || e->attribute("format") != "appended")
      continue;
    const std::size_t offset = std::stoul(e->attribute("offset"));
    const std::string& type = e->attribute("type");
    std::vector<double> values;
    if (type == "Float64")
      values = decode_appended<double>(appended, offset);
    else if (type == "Int64")
      values = decode_appended<std::int64_t>(appended, offset);
    else if (type == "Int32")
      values = decode_appended<std::int32_t>(appended, offset);
    else
      throw std::runtime_error("unexpected DataArray type " + type);
    std::ostringstream text;
    text.precision(17);
    for (double v : values) text << v << ' ';
    e->text = text.str();
  }
  return root;
}

}  // namespace nodus::output::testing
