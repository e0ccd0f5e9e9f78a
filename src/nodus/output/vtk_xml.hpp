#pragma once
/// The writer of a VTK XML PolyData document, shared by the beams' pictures (vtk_format.hpp) and the contact
/// geometry's (contact_vtk.hpp): the document's frame and its data arrays, in either encoding of
/// vtk_encoding.hpp. Internal to the output module.
///
/// Binary documents are those ParaView writes by default: every DataArray is `format="appended"`, its bytes
/// (little-endian) cut into blocks of 32 KiB, each compressed by zlib, and stored after the XML in
/// <AppendedData encoding="raw">, behind a header of UInt64 words [number of blocks, block size, size of the
/// last block if partial (else 0), compressed size of each block] (VTKFile attributes header_type="UInt64",
/// compressor="vtkZLibDataCompressor"). The field TimeValue stays ASCII in both encodings.

#include <cstdint>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include <fmt/format.h>

#include "nodus/output/vtk_encoding.hpp"

namespace nodus::output::vtk_xml {

/// Appends formatted text to a buffer and hands it to the stream in chunks (flushed on destruction).
class ChunkedWriter {
 public:
  explicit ChunkedWriter(std::ostream& out) : out_(out) {}
  ~ChunkedWriter() { flush(); }
  ChunkedWriter(const ChunkedWriter&) = delete;
  ChunkedWriter& operator=(const ChunkedWriter&) = delete;

  template <typename... Args>
  void print(fmt::format_string<Args...> format, Args&&... args) {
    fmt::format_to(std::back_inserter(buffer_), format, std::forward<Args>(args)...);
    if (buffer_.size() > (1u << 20)) flush();
  }
  void write(std::string_view bytes) {
    flush();
    out_.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  void flush() {
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }

 private:
  std::ostream& out_;
  fmt::memory_buffer buffer_;
};

/// Cell counts of a PolyData piece.
struct PieceCounts {
  std::int64_t points = 0;
  std::int64_t lines = 0;
  std::int64_t polys = 0;
};

/// Block size of the compressed arrays [bytes] (VTK's default).
inline constexpr std::size_t kBlockSize = 32768;

/// One PolyData document with one piece, written in order: the constructor writes the frame up to the piece's
/// opening tag; then sections (open/close) and their arrays; finish() closes the document. The ASCII layout:
/// one tuple a line, cell indices sixteen a line.
class PolyDataWriter {
 public:
  /// `time` [s], if given, is stored as the field TimeValue.
  PolyDataWriter(std::ostream& out, VtkEncoding encoding, std::optional<double> time,
                 const PieceCounts& counts);
  PolyDataWriter(const PolyDataWriter&) = delete;
  PolyDataWriter& operator=(const PolyDataWriter&) = delete;

  /// Opens a section of the piece: `tag` is its name and attributes as written ("PointData Scalars=\"beam\"",
  /// "Points", "Lines").
  void open(std::string_view tag);
  /// Closes the section named `name`.
  void close(std::string_view name);

  /// A DataArray named `name` of `values`, `components` values per tuple.
  void array(const char* name, std::span<const std::int32_t> values, int components = 1);
  void array(const char* name, std::span<const double> values, int components = 1);
  /// An Int64 DataArray of cell indices (connectivity, offsets).
  void index_array(const char* name, std::span<const std::int64_t> values);

  /// Closes the piece and the document (with the appended data of a binary one).
  void finish();

 private:
  template <typename T>
  void write_array(const char* type, const char* name, std::span<const T> values, int components,
                   int per_line);

  ChunkedWriter text_;
  VtkEncoding encoding_;
  std::string appended_;  ///< the appended data of a binary document, written by finish()
};

/// The bytes of `size` bytes at `data` as an appended array of a binary document: the header and the
/// compressed blocks described above.
std::string compressed_array(const void* data, std::size_t size);

}  // namespace nodus::output::vtk_xml
