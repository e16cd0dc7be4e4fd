# CMake package for zshift, installed by scripts/install into PREFIX/lib/cmake/zshift.
#
#   find_package(zshift 0.1 REQUIRED)            # CMAKE_PREFIX_PATH must contain PREFIX
#   target_link_libraries(app PRIVATE zshift::zshift)          # shared library
#   target_link_libraries(app PRIVATE zshift::zshift_static)   # or the static one
#
# Both targets carry the include directory holding zshift.h (C) and zshift.hpp (C++17).
# zshift_ABI_VERSION is set to the header's ZSHIFT_ABI_VERSION.
include_guard(GLOBAL)

# PREFIX/lib/cmake/zshift -> PREFIX: the package is relocatable.
get_filename_component(_zshift_prefix "${CMAKE_CURRENT_LIST_DIR}/../../.." ABSOLUTE)
set(_zshift_include "${_zshift_prefix}/include")

foreach(_zshift_file "${_zshift_include}/zshift.h" "${_zshift_prefix}/lib/libzshift.so" "${_zshift_prefix}/lib/libzshift.a")
  if(NOT EXISTS "${_zshift_file}")
    set(zshift_FOUND FALSE)
    set(zshift_NOT_FOUND_MESSAGE "zshift is incompletely installed: ${_zshift_file} is missing")
    return()
  endif()
endforeach()

file(STRINGS "${_zshift_include}/zshift.h" _zshift_abi_line REGEX "^#define ZSHIFT_ABI_VERSION ")
string(REGEX REPLACE "^#define ZSHIFT_ABI_VERSION ([0-9]+).*" "\\1" zshift_ABI_VERSION "${_zshift_abi_line}")

add_library(zshift::zshift SHARED IMPORTED)
set_target_properties(zshift::zshift PROPERTIES
  IMPORTED_LOCATION "${_zshift_prefix}/lib/libzshift.so"
  # cargo's cdylib has no SONAME: link with -lzshift so the executable records "libzshift.so".
  IMPORTED_NO_SONAME TRUE
  INTERFACE_INCLUDE_DIRECTORIES "${_zshift_include}")

# A Rust staticlib needs what Rust's standard library links.
find_package(Threads REQUIRED)
add_library(zshift::zshift_static STATIC IMPORTED)
set_target_properties(zshift::zshift_static PROPERTIES
  IMPORTED_LOCATION "${_zshift_prefix}/lib/libzshift.a"
  INTERFACE_INCLUDE_DIRECTORIES "${_zshift_include}"
  INTERFACE_LINK_LIBRARIES "Threads::Threads;${CMAKE_DL_LIBS};m;rt;util")

unset(_zshift_abi_line)
unset(_zshift_file)
unset(_zshift_include)
unset(_zshift_prefix)
