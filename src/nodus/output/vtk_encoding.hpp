#pragma once
/// How the VTK files of a run store their arrays (the scenario key output.vtk_format; docs/output.md).

namespace nodus::output {

enum class VtkEncoding {
  binary,  ///< raw bytes compressed by zlib, appended after the XML: ParaView's own format, the default
  ascii,   ///< numbers as text inside the XML, 12 significant digits: readable, about ten times larger
};

}  // namespace nodus::output
