# The browser viewer's page (prt web, docs/web.md). web/build.mjs bundles web/src with three.js
# and lil-gui (npm, pinned by web/package-lock.json, installed by scripts/setup.sh) and two
# generated inputs, both in ${PROJECT_BINARY_DIR}/generated/web:
#   constants.js   the library's limits, names, versions and pick order, written at build time
#                  by prt_web_constants (web/gen/constants.cpp, linked against the library);
#   shaders/       the shared stages flattened for WebGL2 (cmake/Shaders.cmake, host webgl2)
# into ${PROJECT_BINARY_DIR}/web, where prt web finds it (or, installed, share/prtkit/web beside
# bin/). Without node or web/node_modules prt builds and `prt web` says what to run.
set(PRT_WEB_OUT ${PROJECT_BINARY_DIR}/web)
set(PRT_WEB_GEN ${PROJECT_BINARY_DIR}/generated/web)
find_program(PRT_NODE node)
if(PRT_NODE AND EXISTS ${PROJECT_SOURCE_DIR}/web/node_modules/three/package.json
   AND EXISTS ${PROJECT_SOURCE_DIR}/web/node_modules/esbuild/package.json
   AND EXISTS ${PROJECT_SOURCE_DIR}/web/node_modules/lil-gui/package.json)
  add_executable(prt_web_constants ${PROJECT_SOURCE_DIR}/web/gen/constants.cpp)
  target_link_libraries(prt_web_constants PRIVATE prt_io prt_relight prt_image prt_warnings
                        prt_codegen)
  add_custom_command(OUTPUT ${PRT_WEB_GEN}/constants.js
    COMMAND prt_web_constants ${PRT_WEB_GEN}/constants.js
    DEPENDS prt_web_constants
    COMMENT "Writing the page's constants from the C++ (web/gen/constants.cpp)")
  include(${CMAKE_CURRENT_LIST_DIR}/Shaders.cmake)
  prt_flatten_shaders(webgl2 ${PRT_WEB_GEN}/shaders ${PRT_SHADER_STAGES_WEB})
  prt_flatten_shaders(three ${PRT_WEB_GEN}/three-shaders ${PRT_SHADER_STAGES_THREE})
  list(TRANSFORM PRT_SHADER_STAGES_WEB PREPEND ${PRT_WEB_GEN}/shaders/ OUTPUT_VARIABLE prt_web_stages)
  list(TRANSFORM PRT_SHADER_STAGES_THREE PREPEND ${PRT_WEB_GEN}/three-shaders/
       OUTPUT_VARIABLE prt_three_stages)
  file(GLOB prt_web_srcs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/web/src/*
       ${PROJECT_SOURCE_DIR}/web/three/*.json ${PROJECT_SOURCE_DIR}/web/three/*.md
       ${PROJECT_SOURCE_DIR}/web/three/src/* ${PROJECT_SOURCE_DIR}/web/three/example/*)
  add_custom_command(OUTPUT ${PRT_WEB_OUT}/prt-web.js ${PRT_WEB_OUT}/index.html
           ${PRT_WEB_OUT}/three/prtkit-three.js ${PRT_WEB_OUT}/three/example/example.js
    COMMAND ${PRT_NODE} ${PROJECT_SOURCE_DIR}/web/build.mjs ${PRT_WEB_OUT} ${PRT_WEB_GEN}
    DEPENDS ${prt_web_srcs} ${prt_web_stages} ${prt_three_stages} ${PRT_WEB_GEN}/constants.js
            ${PROJECT_SOURCE_DIR}/web/build.mjs ${PROJECT_SOURCE_DIR}/web/package-lock.json
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}/web
    COMMENT "Bundling the browser viewer (web/) with esbuild")
  add_custom_target(prt_web_assets ALL DEPENDS ${PRT_WEB_OUT}/prt-web.js ${PRT_WEB_OUT}/index.html)
  add_dependencies(prt_cli prt_web_assets)
  install(DIRECTORY ${PRT_WEB_OUT}/ DESTINATION ${CMAKE_INSTALL_DATADIR}/prtkit/web)
else()
  message(STATUS "prt web: node or web/node_modules not found (run scripts/setup.sh); "
                 "building prt without the browser viewer's page")
endif()
target_compile_definitions(prt_cli PRIVATE PRT_WEB_ASSETS_DIR="${PRT_WEB_OUT}")
