#pragma once
/// Small helpers for the CSV outputs (RFC 4180: comma separated, '\n' line ends, header line first).

#include <string>
#include <string_view>

namespace nodus::output {

/// `text` as one CSV field: unchanged unless it holds a comma, a double quote or a line break, then enclosed
/// in double quotes with inner quotes doubled.
std::string csv_field(std::string_view text);

}  // namespace nodus::output
