# Warnings and sanitizers, applied per target through tmlab_set_target_options().
add_library(tmlab_options INTERFACE)
add_library(tmlab::options ALIAS tmlab_options)
target_compile_options(tmlab_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor)
if(TMLAB_SANITIZE)
  target_compile_options(tmlab_options INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer
                                                 -fno-sanitize-recover=undefined)
  target_link_options(tmlab_options INTERFACE -fsanitize=address,undefined)
endif()
