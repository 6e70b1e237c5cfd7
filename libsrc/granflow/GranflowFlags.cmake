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
if(GRANFLOW_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -g)
  add_link_options(-fsanitize=address,undefined)
endif()
