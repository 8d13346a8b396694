# Included by the root CMakeLists.txt when IGI_FUZZ is ON, before any library is defined.
#
# Every target of this build directory gets AddressSanitizer, UndefinedBehaviorSanitizer and
# libFuzzer's coverage instrumentation: a fuzz target finds little if the libraries it drives
# (igi_common, igi_protocol) are neither checked nor report the edges they reach. UB aborts
# instead of printing and going on, so that libFuzzer sees it as a crash and keeps the input.
# Sets IGI_FUZZ_TARGETS when fuzz/ can be built.

set(IGI_FUZZ_TARGETS OFF)
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(WARNING "IGI_FUZZ needs clang (configure with CC=clang CXX=clang++): "
                  "${CMAKE_CXX_COMPILER_ID} has no libFuzzer, so the fuzz targets are left out")
  return()
endif()

set(IGI_SANITIZE_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=all
                       -fno-omit-frame-pointer)
add_compile_options(${IGI_SANITIZE_FLAGS} -fsanitize=fuzzer-no-link)
add_link_options(${IGI_SANITIZE_FLAGS})
set(IGI_FUZZ_TARGETS ON)
