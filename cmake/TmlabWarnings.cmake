# Warnings and sanitizers, applied per target through tmlab_set_target_options().
add_library(tmlab_options INTERFACE)
add_library(tmlab::options ALIAS tmlab_options)
target_compile_options(tmlab_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor)
if(TMLAB_SANITIZE)
  target_compile_options(tmlab_options INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
                                                 -fno-sanitize-recover=undefined)
  target_link_options(tmlab_options INTERFACE -fsanitize=address,undefined)
endif()
# GCC 12 with -march=native reports -Wmaybe-uninitialized false positives inside Eigen's AVX-512
# intrinsics (avx512fintrin.h) once they are inlined into our code; the warning is unreliable there.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(tmlab_options INTERFACE -Wno-maybe-uninitialized)
endif()
