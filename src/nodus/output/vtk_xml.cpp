#include "nodus/output/vtk_xml.hpp"

namespace nodus::output::vtk_xml {

void begin_polydata(ChunkedWriter& w, std::optional<double> time, const PieceCounts& counts) {
  w.print("<?xml version=\"1.0\"?>\n");
  w.print("<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n");
  w.print("  <PolyData>\n");
  if (time) {
    w.print("    <FieldData>\n");
    w.print(
        "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">{}"
        "</DataArray>\n",
        *time);
    w.print("    </FieldData>\n");
  }
  w.print(
      "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" NumberOfStrips=\"0\" "
      "NumberOfPolys=\"{}\">\n",
      counts.points, counts.lines, counts.polys);
}

void end_polydata(ChunkedWriter& w) {
  w.print("    </Piece>\n");
  w.print("  </PolyData>\n");
  w.print("</VTKFile>\n");
}

void begin_data_array(ChunkedWriter& w, const char* type, const char* name, int components) {
  if (components == 1)
    w.print("        <DataArray type=\"{}\" Name=\"{}\" format=\"ascii\">\n", type, name);
  else
    w.print("        <DataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">\n", type,
            name, components);
}

void end_data_array(ChunkedWriter& w) {
  w.print("        </DataArray>\n");
}

void index_array(ChunkedWriter& w, const char* name, const std::vector<std::int64_t>& values) {
  begin_data_array(w, "Int64", name);
  for (std::size_t i = 0; i < values.size(); ++i) w.print("{}{}", values[i], i % 16 == 15 ? '\n' : ' ');
  w.print("\n");
  end_data_array(w);
}

void cells(ChunkedWriter& w, const char* kind, const std::vector<std::int64_t>& connectivity,
           const std::vector<std::int64_t>& offsets) {
  w.print("      <{}>\n", kind);
  index_array(w, "connectivity", connectivity);
  index_array(w, "offsets", offsets);
  w.print("      </{}>\n", kind);
}

}  // namespace nodus::output::vtk_xml
