# SPDX-License-Identifier: GPL-3.0-or-later
# Compiler settings of every C target of granflow (the library and its
# consumers): C11, warnings are errors, optional sanitizers.  Included by the
# top-level CMakeLists.txt, or by the library's when it is built on its own.
set(CMAKE_C_STANDARD 11)
set(CMAKE_C_STANDARD_REQUIRED ON)
set(CMAKE_C_EXTENSIONS OFF)
if(NOT CMAKE_BUILD_TYPE)
  set(CMAKE_BUILD_TYPE Release)
endif()
option(GRANFLOW_SANITIZE "Build with AddressSanitizer and UBSan" OFF)
find_package(PkgConfig REQUIRED)
add_compile_options(-Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -D_POSIX_C_SOURCE=200809L)
# No contraction of a * b + c into fused multiply-adds (ISO C's default, set
# explicitly): results do not depend on the instruction set the build uses.
add_compile_options(-ffp-contract=off)
# AVX2 for the surface kernel's four-lane vectors (src/surface/, GCC vector
# extensions; without it they take twice the scalar code's time): AUTO
# enables it when the building machine runs AVX2 code (granflow is built
# where it runs; Allwmake), and then compiles for that machine's whole
# instruction set (-march=native: on a host with AVX-512 the four-lane code
# gets 32 vector registers and mask registers; 0.95x the kernel's CPU on the
# 40,000-face bench, 5 paired runs); ON forces -mavx2 alone, OFF neither.
# Results are the same bit for bit every way: IEEE operations are correctly
# rounded on every instruction set, -ffp-contract=off keeps fused
# multiply-adds out, and GCC vectorises no loop whose rounding it would
# change (no -ffast-math).
set(GRANFLOW_AVX2 AUTO CACHE STRING "AVX2 code in libgranflow: AUTO (the host's instruction set), ON or OFF")
set_property(CACHE GRANFLOW_AVX2 PROPERTY STRINGS AUTO ON OFF)
set(granflow_native OFF)
if(GRANFLOW_AVX2 STREQUAL "AUTO")
  include(CheckCSourceRuns)
  include(CheckCCompilerFlag)
  set(CMAKE_REQUIRED_FLAGS -mavx2)
  check_c_source_runs("int main(void) { __builtin_cpu_init(); return __builtin_cpu_supports(\"avx2\") ? 0 : 1; }"
                      GRANFLOW_HOST_AVX2)
  unset(CMAKE_REQUIRED_FLAGS)
  set(granflow_avx2 ${GRANFLOW_HOST_AVX2})
  if(granflow_avx2)
    check_c_compiler_flag(-march=native GRANFLOW_CC_NATIVE)
    set(granflow_native ${GRANFLOW_CC_NATIVE})
  endif()
elseif(GRANFLOW_AVX2)
  set(granflow_avx2 ON)
else()
  set(granflow_avx2 OFF)
endif()
if(granflow_native)
  add_compile_options(-march=native)
elseif(granflow_avx2)
  add_compile_options(-mavx2)
endif()
if(GRANFLOW_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -g)
  add_link_options(-fsanitize=address,undefined)
endif()
