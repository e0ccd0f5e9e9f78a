#pragma once
/// The script of `nodus view`'s page: web/src bundled with three.js by esbuild when nodus is built, and
/// compiled into the library (cmake/viewer.cmake generates its definition).

#include <string_view>

namespace nodus::output {

/// The bundled script (minified JavaScript, ASCII); empty when nodus was built without web/node_modules.
std::string_view viewer_bundle();

}  // namespace nodus::output
