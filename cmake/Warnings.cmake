# Project-wide compile flags. -ffp-contract=off keeps results bit-identical across builds
# (no fused multiply-add changing roundings), see STYLE.md "Robustness".
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
install(TARGETS constrict_flags EXPORT constrictTargets)
