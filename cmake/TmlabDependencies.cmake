# Third-party dependencies, all from Debian 12 packages (no downloads at build time).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(Threads REQUIRED)
# GSL 2.7 (libgsl-dev): special functions, simulated annealing and nonlinear least squares (calibration/).
find_package(GSL 2.7 REQUIRED)

# HDF5: deal.II (reference_fem) links the OpenMPI flavour, so every tmlab program uses that same
# flavour (libhdf5-openmpi-dev) and never the serial one. The C API needs mpi.h on the include path.
find_package(MPI REQUIRED COMPONENTS C)
find_path(TMLAB_HDF5_INCLUDE_DIR hdf5.h PATHS /usr/include/hdf5/openmpi NO_DEFAULT_PATH REQUIRED)
find_library(TMLAB_HDF5_LIBRARY hdf5 PATHS /usr/lib/x86_64-linux-gnu/hdf5/openmpi NO_DEFAULT_PATH REQUIRED)
add_library(tmlab_hdf5 INTERFACE)
add_library(tmlab::hdf5 ALIAS tmlab_hdf5)
target_include_directories(tmlab_hdf5 SYSTEM INTERFACE ${TMLAB_HDF5_INCLUDE_DIR})
target_link_libraries(tmlab_hdf5 INTERFACE ${TMLAB_HDF5_LIBRARY} MPI::MPI_C)

if(TMLAB_BUILD_TESTS)
  find_package(GTest 1.12 REQUIRED)
endif()
if(TMLAB_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()

# SuiteSparse CHOLMOD (libsuitesparse-dev): the sparse Cholesky of the Newton solves with
# solver.linear = "cholmod" (tensormass/solvers/newton.hpp), through Eigen's CholmodSupport.
# Debian 12 ships SuiteSparse 5.12 without CMake package files: header and libraries by path.
find_path(TMLAB_CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(TMLAB_CHOLMOD_LIBRARY cholmod REQUIRED)
find_library(TMLAB_SUITESPARSECONFIG_LIBRARY suitesparseconfig REQUIRED)
add_library(tmlab_cholmod INTERFACE)
add_library(tmlab::cholmod ALIAS tmlab_cholmod)
target_include_directories(tmlab_cholmod SYSTEM INTERFACE ${TMLAB_CHOLMOD_INCLUDE_DIR})
target_link_libraries(tmlab_cholmod INTERFACE ${TMLAB_CHOLMOD_LIBRARY} ${TMLAB_SUITESPARSECONFIG_LIBRARY})
