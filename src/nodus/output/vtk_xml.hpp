#pragma once
/// Building blocks shared by the VTK XML PolyData writers (vtk_format.hpp for the beams, contact_vtk.hpp for
/// the contact geometry): a buffered formatter and the pieces of the document that do not depend on what is
/// drawn. Internal to the output module.

#include <cstdint>
#include <optional>
#include <ostream>
#include <utility>
#include <vector>

#include <fmt/format.h>

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

/// The XML declaration, <VTKFile type="PolyData">, <PolyData>, the field TimeValue [s] if `time` is given,
/// and the opening <Piece> tag with `counts` (no vertices, no strips).
void begin_polydata(ChunkedWriter& w, std::optional<double> time, const PieceCounts& counts);

/// Closes what begin_polydata opened.
void end_polydata(ChunkedWriter& w);

/// Opens a DataArray of `type` (Int32, Int64, Float64) named `name` with `components` values per tuple.
void begin_data_array(ChunkedWriter& w, const char* type, const char* name, int components = 1);

/// Closes a DataArray.
void end_data_array(ChunkedWriter& w);

/// A whole Int64 DataArray named `name` (cell connectivity or offsets), sixteen values per line.
void index_array(ChunkedWriter& w, const char* name, const std::vector<std::int64_t>& values);

/// The <Points> element with `count` points; point_of(p) gives point p (indexable by 0, 1, 2) [mm].
template <typename PointOf>
void points(ChunkedWriter& w, std::int64_t count, PointOf point_of) {
  w.print("      <Points>\n");
  w.print("        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (std::int64_t p = 0; p < count; ++p) {
    const auto q = point_of(p);
    w.print("{:.12g} {:.12g} {:.12g}\n", q[0], q[1], q[2]);
  }
  w.print("        </DataArray>\n");
  w.print("      </Points>\n");
}

/// A <Lines> or <Polys> element (`kind`) with its connectivity and offsets arrays.
void cells(ChunkedWriter& w, const char* kind, const std::vector<std::int64_t>& connectivity,
           const std::vector<std::int64_t>& offsets);

}  // namespace nodus::output::vtk_xml
