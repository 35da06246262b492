# Compiler warnings and sanitizers applied to every Tessera target.

# No contraction of a * b + c into fused multiply-adds: every SIMD target and the scalar code
# must round the same way, so that images are the same bytes on every target.
add_compile_options(-ffp-contract=off)

# GCC's -fsanitize=undefined leaves out float-cast-overflow (a float out of an integer's range,
# or NaN, converted to it); Clang's includes it. Both builds check it.
if(TESSERA_SANITIZE)
  add_compile_options(-fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer
                      -fno-sanitize-recover=all)
  add_link_options(-fsanitize=address,undefined,float-cast-overflow)
endif()
# ThreadSanitizer for the multithreaded paths (the tsan preset). It cannot share a build with
# AddressSanitizer.
if(TESSERA_TSAN)
  if(TESSERA_SANITIZE)
    message(FATAL_ERROR "TESSERA_TSAN and TESSERA_SANITIZE cannot be combined")
  endif()
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif()
# Coverage instrumentation for libFuzzer in every target; only the fuzz targets link the
# fuzzer's main (tests/fuzz/CMakeLists.txt).
if(TESSERA_FUZZING)
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

function(tessera_set_warnings target)
  # -Wnon-virtual-dtor is C++ only (the C API's test and example are C).
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion
                                           $<$<COMPILE_LANGUAGE:CXX>:-Wnon-virtual-dtor>)
  if(TESSERA_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
