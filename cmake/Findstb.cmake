# Findstb: Debian's libstb-dev (the stb single-file libraries built as a
# library: /usr/include/stb/stb_*.h, libstb.so and libstb.a).
#
# Imported targets:
#   stb::stb         the shared libstb.so, with the include folder that holds
#                    stb_image.h (<prefix>/include/stb)
#   stb::stb_static  libstb.a, when it exists (the rayform program and the fuzz
#                    binaries link it: rayform_stb_first, pipeline/CMakeLists.txt)
# Variables: stb_FOUND, stb_INCLUDE_DIR, stb_LIBRARY, stb_STATIC_LIBRARY.
find_path(stb_INCLUDE_DIR stb_image_write.h PATH_SUFFIXES stb)
find_library(stb_LIBRARY NAMES ${CMAKE_SHARED_LIBRARY_PREFIX}stb${CMAKE_SHARED_LIBRARY_SUFFIX} stb)
find_library(stb_STATIC_LIBRARY NAMES ${CMAKE_STATIC_LIBRARY_PREFIX}stb${CMAKE_STATIC_LIBRARY_SUFFIX})
mark_as_advanced(stb_INCLUDE_DIR stb_LIBRARY stb_STATIC_LIBRARY)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(stb REQUIRED_VARS stb_LIBRARY stb_INCLUDE_DIR)

if(stb_FOUND AND NOT TARGET stb::stb)
  add_library(stb::stb UNKNOWN IMPORTED)
  set_target_properties(stb::stb PROPERTIES IMPORTED_LOCATION "${stb_LIBRARY}"
                                            INTERFACE_INCLUDE_DIRECTORIES "${stb_INCLUDE_DIR}")
endif()
if(stb_FOUND AND stb_STATIC_LIBRARY AND NOT TARGET stb::stb_static)
  add_library(stb::stb_static STATIC IMPORTED)
  set_target_properties(stb::stb_static PROPERTIES IMPORTED_LOCATION "${stb_STATIC_LIBRARY}"
                                                   INTERFACE_INCLUDE_DIRECTORIES "${stb_INCLUDE_DIR}")
endif()
