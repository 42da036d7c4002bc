# Install rules (RAYFORM_INSTALL, on by default when rayform is the top-level
# project). The installed layout:
#   <prefix>/bin/rayform                           the command-line program
#   <prefix>/lib/librayform_core.a, librayform_importers.a, librayform_pipeline.a
#   <prefix>/lib/rayform/librayform_oiio.so        the OpenImageIO plugin (dlopen'ed)
#   <prefix>/lib/rayform/librayform_mpi.so         the MPI plugin (dlopen'ed under mpirun; with RAYFORM_MPI)
#   <prefix>/include/rayform/<folder>/*.h          src/<folder>/*.h
#   <prefix>/include/rayform/importers/...         importers/**/*.h, less the readers' internals
#   <prefix>/include/rayform/pipeline/*.h          pipeline/*.h
#   <prefix>/lib/cmake/rayform/                    rayformConfig.cmake, rayformConfigVersion.cmake,
#                                                  rayformTargets*.cmake, Findstb.cmake
#   <prefix>/lib/pkgconfig/rayform.pc
# (lib is CMAKE_INSTALL_LIBDIR: lib/<multiarch> for the prefix /usr on Debian.)
include(CMakePackageConfigHelpers)

set(RAYFORM_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/rayform" CACHE STRING
    "Where rayformConfig.cmake is installed, relative to the install prefix")

install(TARGETS rayform_core rayform_importers rayform_pipeline rayform_stb_first EXPORT rayformTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS rayform_oiio LIBRARY DESTINATION ${RAYFORM_INSTALL_PLUGINDIR})
if(TARGET rayform)
  install(TARGETS rayform RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  if(TARGET rayform_mpi)
    install(TARGETS rayform_mpi LIBRARY DESTINATION ${RAYFORM_INSTALL_PLUGINDIR})
  endif()
endif()

# Headers: every header of the libraries, under the path the sources include
# it by, except those private to one source file: the readers' internals
# (some include tiny_gltf.h, tiny_obj_loader.h or oneTBB: private dependencies
# a consumer does not have), the traversal kernels that mesh_accel_traverse.cpp
# includes once per instruction set, and the mesh BVH builder's internals
# (mesh_accel_builder.h and the mesh_build_*.h it includes; oneTBB too) that
# mesh_accel_build.cpp and mesh_accel_share.cpp share. No installed header
# includes them
# (tests/package compiles every installed header with nothing but
# rayform::core's usage requirements).
set(RAYFORM_PRIVATE_HEADERS src/accel/mesh_accel_builder.h src/accel/mesh_build_flatten.h src/accel/mesh_build_refs.h
                            src/accel/mesh_build_split.h src/accel/mesh_build_tree.h
                            src/accel/mesh_accel_kernel.h src/accel/mesh_accel_packet8.h
                            importers/gltf/gltf_accessors.h importers/gltf/gltf_writer_internal.h
                            importers/gltf/gltf_file_access.h importers/gltf/gltf_reader_internal.h
                            importers/obj/mtl_library.h importers/obj/obj_materials.h importers/obj/obj_text_bounds.h importers/obj/obj_parallel_parse.h
                            importers/obj/obj_parse_bytes.h importers/obj/obj_plain_chunk.h importers/obj/obj_polygon_split.h
                            importers/obj/obj_smooth_normals.h importers/obj/obj_vertex_weld.h
                            importers/course_txt/course_writer_internal.h importers/file_bytes.h)
set(_exclude "")
foreach(_h ${RAYFORM_PRIVATE_HEADERS})
  string(REPLACE "." "\\." _h "${_h}")
  list(APPEND _exclude REGEX "/${_h}$" EXCLUDE)
endforeach()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rayform
        FILES_MATCHING PATTERN "*.h" ${_exclude})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/importers/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rayform/importers
        FILES_MATCHING PATTERN "*.h" ${_exclude})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/pipeline/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/rayform/pipeline
        FILES_MATCHING PATTERN "*.h")

# The CMake package: rayform::core, rayform::importers and rayform::pipeline.
install(EXPORT rayformTargets NAMESPACE rayform:: DESTINATION ${RAYFORM_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/rayformConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/rayformConfig.cmake
                              INSTALL_DESTINATION ${RAYFORM_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/rayformConfigVersion.cmake
                                 COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/rayformConfig.cmake ${PROJECT_BINARY_DIR}/rayformConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/Findstb.cmake
        DESTINATION ${RAYFORM_INSTALL_CMAKEDIR})

# rayform.pc, relocatable: its prefix is found from its own folder.
set(_pc_dir "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
file(RELATIVE_PATH _pc_to_prefix "/root/${_pc_dir}" "/root")
string(REGEX REPLACE "/$" "" _pc_to_prefix "${_pc_to_prefix}")
set(RAYFORM_PC_PREFIX "\${pcfiledir}/${_pc_to_prefix}")
configure_file(${PROJECT_SOURCE_DIR}/cmake/rayform.pc.in ${PROJECT_BINARY_DIR}/rayform.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/rayform.pc DESTINATION ${_pc_dir})
