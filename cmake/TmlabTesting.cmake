# tmlab_add_gtest(NAME name SOURCES ... LIBS ... LABELS ... TIMEOUT seconds)
# One executable per test file group; every test gets labels and a timeout.
# Labels in use: unit, kernel, verification, reference, mpi, fast, slow.
function(tmlab_add_gtest)
  cmake_parse_arguments(T "" "NAME;TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  if(NOT TMLAB_BUILD_TESTS)
    return()
  endif()
  if(NOT T_TIMEOUT)
    set(T_TIMEOUT 120)
  endif()
  add_executable(${T_NAME} ${T_SOURCES})
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest tmlab::gtest_main tmlab::options)
  target_compile_definitions(${T_NAME} PRIVATE TMLAB_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  add_test(NAME ${T_NAME} COMMAND ${T_NAME} --gtest_brief=1)
  set_tests_properties(${T_NAME} PROPERTIES LABELS "${T_LABELS}" TIMEOUT ${T_TIMEOUT})
  tmlab_gtest_skips(${T_NAME})
endfunction()

# A gtest executable exits 77 when it passed with a skipped test (core/testing/gtest_exit.hpp):
# ctest then reports the test as skipped, never as passed. Every add_test of a gtest executable
# (tmlab_add_gtest does it itself) calls this.
function(tmlab_gtest_skips test_name)
  set_tests_properties(${test_name} PROPERTIES SKIP_RETURN_CODE 77)
endfunction()

# Tests whose processes start MPI (the deal.II reference, and the CLI that may run it): under the
# asan-ubsan preset, LeakSanitizer reports the allocations OpenMPI keeps until exit from components
# it has already unloaded (no symbol can be suppressed), so leak detection is switched off for these
# tests only. AddressSanitizer and UBSan still check them; every other test keeps leak detection.
function(tmlab_mpi_test_environment test_name)
  if(TMLAB_SANITIZE AND TEST ${test_name})
    set_property(TEST ${test_name} APPEND PROPERTY ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0")
  endif()
endfunction()

# tmlab_add_module(NAME n SOURCES ... [PUBLIC ...] [PRIVATE ...])
# One concept folder = one static library tmlab_<n>, alias tmlab::<n>. Headers sit beside their
# sources and are included from the repository root ("tensormass/kernels/tensor_mass.hpp"), so the
# include path names the folder a reader finds the file in. A module without sources is INTERFACE.
function(tmlab_add_module)
  cmake_parse_arguments(M "" "NAME" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  if(M_SOURCES)
    add_library(tmlab_${M_NAME} ${M_SOURCES})
    target_include_directories(tmlab_${M_NAME} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
                                                      $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/generated>)
    target_link_libraries(tmlab_${M_NAME} PUBLIC ${M_PUBLIC} PRIVATE ${M_PRIVATE} tmlab::options)
  else()
    add_library(tmlab_${M_NAME} INTERFACE)
    target_include_directories(tmlab_${M_NAME} INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>)
    target_link_libraries(tmlab_${M_NAME} INTERFACE ${M_PUBLIC})
  endif()
  add_library(tmlab::${M_NAME} ALIAS tmlab_${M_NAME})
endfunction()
