#include "nodus/output/vtk_xml.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include <zlib.h>

namespace nodus::output::vtk_xml {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the VTK files say byte_order=\"LittleEndian\" and store the host's bytes");

void append_words(std::string& out, const std::vector<std::uint64_t>& words) {
  out.append(reinterpret_cast<const char*>(words.data()), words.size() * sizeof(std::uint64_t));
}

}  // namespace

std::string compressed_array(const void* data, std::size_t size) {
  const auto* bytes = static_cast<const Bytef*>(data);
  const std::size_t blocks = (size + kBlockSize - 1) / kBlockSize;
  std::vector<std::uint64_t> header{blocks, kBlockSize, size % kBlockSize};
  std::string compressed;
  std::vector<Bytef> block(compressBound(kBlockSize));
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t first = b * kBlockSize;
    const std::size_t length = std::min(kBlockSize, size - first);
    uLongf written = static_cast<uLongf>(block.size());
    if (compress2(block.data(), &written, bytes + first, static_cast<uLong>(length), Z_DEFAULT_COMPRESSION) !=
        Z_OK)
      throw std::runtime_error("VTK output: zlib could not compress an array");
    header.push_back(written);
    compressed.append(reinterpret_cast<const char*>(block.data()), written);
  }
  std::string out;
  out.reserve(header.size() * sizeof(std::uint64_t) + compressed.size());
  append_words(out, header);
  out += compressed;
  return out;
}

PolyDataWriter::PolyDataWriter(std::ostream& out, VtkEncoding encoding, std::optional<double> time,
                               const PieceCounts& counts)
    : text_(out), encoding_(encoding) {
  text_.print("<?xml version=\"1.0\"?>\n");
  if (encoding_ == VtkEncoding::binary)
    text_.print(
        "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\" "
        "compressor=\"vtkZLibDataCompressor\">\n");
  else
    text_.print("<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
  text_.print("  <PolyData>\n");
  if (time) {
    text_.print("    <FieldData>\n");
    text_.print(
        "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">{}"
        "</DataArray>\n",
        *time);
    text_.print("    </FieldData>\n");
  }
  text_.print(
      "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" NumberOfStrips=\"0\" "
      "NumberOfPolys=\"{}\">\n",
      counts.points, counts.lines, counts.polys);
}

void PolyDataWriter::open(std::string_view tag) {
  text_.print("      <{}>\n", tag);
}

void PolyDataWriter::close(std::string_view name) {
  text_.print("      </{}>\n", name);
}

void PolyDataWriter::array(const char* name, std::span<const std::int32_t> values, int components) {
  write_array("Int32", name, values, components, components);
}

void PolyDataWriter::array(const char* name, std::span<const double> values, int components) {
  write_array("Float64", name, values, components, components);
}

void PolyDataWriter::index_array(const char* name, std::span<const std::int64_t> values) {
  write_array("Int64", name, values, 1, 16);
}

template <typename T>
void PolyDataWriter::write_array(const char* type, const char* name, std::span<const T> values,
                                 int components, int per_line) {
  text_.print("        <DataArray type=\"{}\" Name=\"{}\"", type, name);
  if (components != 1) text_.print(" NumberOfComponents=\"{}\"", components);
  if (encoding_ == VtkEncoding::binary) {
    text_.print(" format=\"appended\" offset=\"{}\"/>\n", appended_.size());
    appended_ += compressed_array(values.data(), values.size_bytes());
    return;
  }
  text_.print(" format=\"ascii\">\n");
  const auto count = static_cast<std::ptrdiff_t>(values.size());
  for (std::ptrdiff_t i = 0; i < count; ++i) {
    const char separator = i % per_line == per_line - 1 ? '\n' : ' ';
    if constexpr (std::is_floating_point_v<T>)
      text_.print("{:.12g}{}", values[static_cast<std::size_t>(i)], separator);
    else
      text_.print("{}{}", values[static_cast<std::size_t>(i)], separator);
  }
  // Cell indices end with a line break of their own, after a full line too.
  if (per_line != components) text_.print("\n");
  text_.print("        </DataArray>\n");
}

void PolyDataWriter::finish() {
  text_.print("    </Piece>\n");
  text_.print("  </PolyData>\n");
  if (encoding_ == VtkEncoding::binary) {
    text_.print("  <AppendedData encoding=\"raw\">\n   _");
    text_.write(appended_);
    text_.print("\n  </AppendedData>\n");
  }
  text_.print("</VTKFile>\n");
}

}  // namespace nodus::output::vtk_xml
