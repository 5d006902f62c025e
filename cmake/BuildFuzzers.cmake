# ctest fixture fuzz.build: configures and builds the clang sub-project fuzz/ into BIN.
# Usage: cmake -DSRC=<tmlab>/fuzz -DBIN=<build>/fuzz -DCXX=clang++ -P BuildFuzzers.cmake
foreach(v SRC BIN CXX)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "BuildFuzzers.cmake: -D${v}=... is required")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SRC} -B ${BIN} -DCMAKE_CXX_COMPILER=${CXX}
                        -DCMAKE_BUILD_TYPE=RelWithDebInfo
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz.build: configuring ${SRC} with ${CXX} failed (is libclang-rt-14-dev installed?)")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BIN} -j 2 RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fuzz.build: building the fuzzers in ${BIN} failed")
endif()
