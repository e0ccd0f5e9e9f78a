# The page script of `nodus view` (docs/view.md): web/src and three.js bundled by esbuild (web/build.mjs) from
# web/node_modules, which scripts/setup.sh installs with `npm ci`; nothing is downloaded here. The bundle is
# compiled into nodus_core as nodus::output::viewer_bundle() (cmake/embed_viewer.cmake). Without node or
# web/node_modules the library gets an empty bundle, and `nodus view` says how to get the page (exit status 2).
set(_nodus_web "${PROJECT_SOURCE_DIR}/web")
set(_nodus_viewer_cpp "${PROJECT_BINARY_DIR}/generated/viewer_bundle.cpp")
find_program(NODUS_NODE NAMES node nodejs DOC "Node.js, to bundle the page script of nodus view")
# Configure again when web/node_modules comes or goes (web/'s time changes with its entries).
set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${_nodus_web}")
set(NODUS_VIEWER OFF)
if(NODUS_NODE AND EXISTS "${_nodus_web}/node_modules/esbuild/package.json"
   AND EXISTS "${_nodus_web}/node_modules/three/package.json")
  set(NODUS_VIEWER ON)
  file(GLOB _nodus_web_sources CONFIGURE_DEPENDS "${_nodus_web}/src/*.js")
  set(_nodus_viewer_js "${PROJECT_BINARY_DIR}/generated/viewer.js")
  add_custom_command(OUTPUT "${_nodus_viewer_js}"
    COMMAND "${NODUS_NODE}" "${_nodus_web}/build.mjs" "${_nodus_viewer_js}"
    DEPENDS ${_nodus_web_sources} "${_nodus_web}/build.mjs" "${_nodus_web}/package-lock.json"
    COMMENT "Bundling the page script of nodus view (web/)" VERBATIM)
  add_custom_command(OUTPUT "${_nodus_viewer_cpp}"
    COMMAND "${CMAKE_COMMAND}" "-DIN=${_nodus_viewer_js}" "-DOUT=${_nodus_viewer_cpp}"
            -P "${PROJECT_SOURCE_DIR}/cmake/embed_viewer.cmake"
    DEPENDS "${_nodus_viewer_js}" "${PROJECT_SOURCE_DIR}/cmake/embed_viewer.cmake" VERBATIM)
else()
  message(WARNING "web/node_modules (or node) missing: `nodus view` is built without its page; run "
                  "scripts/setup.sh (npm ci in web/) and build again")
  execute_process(COMMAND "${CMAKE_COMMAND}" "-DOUT=${_nodus_viewer_cpp}"
                          -P "${PROJECT_SOURCE_DIR}/cmake/embed_viewer.cmake")
endif()
target_sources(nodus_core PRIVATE "${_nodus_viewer_cpp}")
