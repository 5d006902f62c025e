# Build identity for manifests: git SHA (and whether the tree was dirty), build type, compiler.
# Re-evaluated at every build through a generated header so manifests never carry a stale SHA.
set(TMLAB_VERSION_IN ${CMAKE_CURRENT_LIST_DIR}/build_info.hpp.in)
string(TOUPPER "${CMAKE_BUILD_TYPE}" _tmlab_bt)
add_custom_target(tmlab_build_info
  COMMAND ${CMAKE_COMMAND} "-DSRC=${PROJECT_SOURCE_DIR}"
          "-DOUT=${PROJECT_BINARY_DIR}/generated/tmlab/build_info.hpp"
          "-DIN=${TMLAB_VERSION_IN}" "-DBUILD_TYPE=${CMAKE_BUILD_TYPE}"
          "-DCOMPILER=${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER_VERSION}"
          "-DFLAGS=${CMAKE_CXX_FLAGS} ${CMAKE_CXX_FLAGS_${_tmlab_bt}}"
          -P ${CMAKE_CURRENT_LIST_DIR}/GenerateBuildInfo.cmake
  BYPRODUCTS ${PROJECT_BINARY_DIR}/generated/tmlab/build_info.hpp
  COMMENT "Recording git SHA for manifests"
  VERBATIM)
