# The project's compile flags, for its own targets only: each links constrict_flags PRIVATE
# (constrict_lib through BUILD_INTERFACE), and it is not exported, so an installed constrict
# imposes none of them on its consumers (tests/consumer checks). -ffp-contract=off keeps results
# bit-identical across builds (no fused multiply-add changing roundings), STYLE.md "Robustness".
add_library(constrict_flags INTERFACE)
target_compile_options(constrict_flags INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -ffp-contract=off>)
if(CONSTRICT_WERROR)
  target_compile_options(constrict_flags INTERFACE $<$<CXX_COMPILER_ID:GNU,Clang>:-Werror>)
endif()
if(CONSTRICT_SANITIZE)
  target_compile_options(constrict_flags INTERFACE -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(constrict_flags INTERFACE -fsanitize=address,undefined)
endif()
