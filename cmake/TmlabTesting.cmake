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
  target_link_libraries(${T_NAME} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main tmlab::options)
  target_compile_definitions(${T_NAME} PRIVATE TMLAB_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                               TMLAB_SHARED_DIR="${PROJECT_SOURCE_DIR}/../shared")
  add_test(NAME ${T_NAME} COMMAND ${T_NAME} --gtest_brief=1)
  set_tests_properties(${T_NAME} PROPERTIES LABELS "${T_LABELS}" TIMEOUT ${T_TIMEOUT})
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
