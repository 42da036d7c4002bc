# tests/package (cmake -P): rayform used by an outside project, the consumer
# of tests/package/consumer (examples/render_scene.cpp). The two modes share
# one build of rayform's libraries (the slow part), in this order (ctest
# fixture rayform_package_build):
#   MODE=subdirectory  empty WORK, build the consumer with
#                      add_subdirectory(SOURCE_DIR), no CMAKE_CXX_STANDARD nor
#                      CMAKE_BUILD_TYPE of its own; rayform adds none of its
#                      tests, benchmarks or CLI there. The build is kept.
#   MODE=install       turn on rayform's install rules and CLI in that build
#                      (RAYFORM_INSTALL, RAYFORM_CLI: only the CLI is compiled
#                      more), `cmake --install` it to WORK/prefix, delete the
#                      build, then build the consumer with find_package(rayform)
#                      and check rayform.pc with pkg-config (flags, and a
#                      program compiled and linked with them alone)
# Either way the consumer renders SOURCE_DIR/scenes/default.txt to a BMP that
# must be a 64x48 picture with more than one colour, and to a TIFF, written
# through the OpenImageIO plugin (librayform_oiio.so, dlopen'ed), that must
# exist and not be empty.
# Needs: SOURCE_DIR, WORK, MODE; optional JOBS (default 2).
foreach(v SOURCE_DIR WORK MODE)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "package_test.cmake needs -D${v}=...")
  endif()
endforeach()
if(NOT DEFINED JOBS)
  set(JOBS 2)
endif()

string(TIMESTAMP started "%s")
# Each step's command and time in the test's output (ctest -V).
function(run)
  string(TIMESTAMP t0 "%s")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    list(JOIN ARGN " " cmd)
    message(FATAL_ERROR "failed (${rc}): ${cmd}\n${out}${err}")
  endif()
  string(TIMESTAMP t1 "%s")
  math(EXPR dt "${t1} - ${t0}")
  list(GET ARGN 1 what)
  list(GET ARGN 0 program)
  get_filename_component(program "${program}" NAME)
  message(STATUS "${dt} s: ${program} ${what}")
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

# A BMP written by rayform (24-bit, bottom-up): W x H and not every pixel the
# colour of the first.
function(check_bmp path w h)
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "${path} was not written")
  endif()
  file(SIZE "${path}" size)
  file(READ "${path}" magic LIMIT 2 HEX)
  if(NOT magic STREQUAL "424d" OR size LESS 54)  # "BM"
    message(FATAL_ERROR "${path} is not a BMP (${size} bytes)")
  endif()
  foreach(field "offset;10" "width;18" "height;22")
    list(GET field 0 name)
    list(GET field 1 at)
    file(READ "${path}" le OFFSET ${at} LIMIT 4 HEX)
    string(REGEX REPLACE "(..)(..)(..)(..)" "\\4\\3\\2\\1" be "${le}")
    math(EXPR ${name} "0x${be}")
  endforeach()
  if(NOT width EQUAL w OR NOT height EQUAL h)
    message(FATAL_ERROR "${path} is ${width}x${height}, expected ${w}x${h}")
  endif()
  math(EXPR bytes "${w} * ${h} * 3")  # rows unpadded: w * 3 is a multiple of 4 for the sizes used here
  file(READ "${path}" pixels OFFSET ${offset} LIMIT ${bytes} HEX)
  string(SUBSTRING "${pixels}" 0 6 first)
  math(EXPR count "${w} * ${h}")
  string(REPEAT "${first}" ${count} uniform)
  if(pixels STREQUAL uniform)
    message(FATAL_ERROR "${path} is blank: every pixel is ${first} (BGR)")
  endif()
endfunction()

function(check_render program)
  set(scene "${SOURCE_DIR}/scenes/default.txt")
  file(REMOVE "${WORK}/out.bmp" "${WORK}/out.tif")
  run("${program}" "${scene}" "${WORK}/out.bmp" 64 48)
  check_bmp("${WORK}/out.bmp" 64 48)
  run("${program}" "${scene}" "${WORK}/out.tif" 64 48)
  file(SIZE "${WORK}/out.tif" size)
  if(NOT size GREATER 0)
    message(FATAL_ERROR "${WORK}/out.tif is empty")
  endif()
  message(STATUS "${program}: a 64x48 BMP that is not blank, and a TIFF of ${size} bytes")
endfunction()

set(consumer_src "${SOURCE_DIR}/tests/package/consumer")
set(shared_build "${WORK}/subproject")  # the consumer with rayform as its subdirectory
set(prefix "${WORK}/prefix")
# The nested build compiles rayform once more, as cheaply as it can: no
# optimisation and no debug information (no build type: no flags of its own),
# no ccache.
set(common -G Ninja -DCMAKE_CXX_COMPILER_LAUNCHER=)

if(MODE STREQUAL "subdirectory")
  file(REMOVE_RECURSE "${WORK}")
  file(MAKE_DIRECTORY "${WORK}")
  unset(ENV{CMAKE_BUILD_TYPE})  # CMake's default for a new build folder: the consumer chooses none
  # The install prefix is named now, for the install mode's use of this build
  # (the plugin's install folder is compiled into the library).
  run(${CMAKE_COMMAND} -S "${consumer_src}" -B "${shared_build}" ${common} -DRAYFORM_CONSUMER_MODE=subdirectory
      "-DRAYFORM_DIR=${SOURCE_DIR}" "-DCMAKE_INSTALL_PREFIX=${prefix}")
  # rayform as a subproject: no build type forced on the consumer, none of
  # rayform's tests, benchmarks or CLI in its build.
  file(STRINGS "${shared_build}/CMakeCache.txt" build_type REGEX "^CMAKE_BUILD_TYPE:")
  if(NOT build_type MATCHES "^CMAKE_BUILD_TYPE:[A-Z]+=$")
    message(FATAL_ERROR "rayform set the consumer's build type: ${build_type}")
  endif()
  run(${CMAKE_COMMAND} --build "${shared_build}" --target help)
  foreach(t rayform rayform_unit_tests rayform_example_render rayform_bench_render)
    if(run_output MATCHES "(^|\n)${t}:")
      message(FATAL_ERROR "the consumer's build has rayform's target ${t}")
    endif()
  endforeach()
  run(${CMAKE_COMMAND} --build "${shared_build}" -j ${JOBS})
  check_render("${shared_build}/consumer_render")
elseif(MODE STREQUAL "install")
  if(NOT EXISTS "${shared_build}/CMakeCache.txt")
    message(FATAL_ERROR "${shared_build} is missing: package.subdirectory makes it (run both tests)")
  endif()
  file(REMOVE_RECURSE "${prefix}" "${WORK}/consumer")
  # rayform's own install rules and CLI, off in a subproject by default.
  run(${CMAKE_COMMAND} "${shared_build}" -DRAYFORM_INSTALL=ON -DRAYFORM_CLI=ON)
  run(${CMAKE_COMMAND} --build "${shared_build}" -j ${JOBS})
  run(${CMAKE_COMMAND} --install "${shared_build}")
  file(STRINGS "${shared_build}/CMakeCache.txt" with_mpi REGEX "^RAYFORM_MPI:BOOL=ON$")
  # Nothing may refer to the build tree any more (the plugin is found in the
  # prefix, where the CLI and the compiled-in install folder point).
  file(REMOVE_RECURSE "${shared_build}")
  foreach(f bin/rayform lib/rayform/librayform_oiio.so lib/librayform_core.a lib/librayform_importers.a lib/librayform_pipeline.a
            lib/cmake/rayform/rayformConfig.cmake lib/cmake/rayform/rayformConfigVersion.cmake
            lib/cmake/rayform/rayformTargets.cmake lib/pkgconfig/rayform.pc include/rayform/scene/scene.h
            include/rayform/importers/scene_io.h)
    if(NOT EXISTS "${prefix}/${f}")
      message(FATAL_ERROR "not installed: ${prefix}/${f}")
    endif()
  endforeach()
  # The installed CLI: the plugin from ../lib/rayform beside it.
  file(REMOVE "${WORK}/cli.tif")
  run("${prefix}/bin/rayform" render "${SOURCE_DIR}/scenes/default.txt" -o "${WORK}/cli.tif" --size 32x24)
  if(NOT EXISTS "${WORK}/cli.tif")
    message(FATAL_ERROR "the installed rayform did not write ${WORK}/cli.tif")
  endif()
  # Built with MPI: the MPI plugin installed beside the OpenImageIO one, and
  # found there by the installed CLI under mpirun.
  find_program(mpirun mpirun)
  if(with_mpi AND mpirun)
    if(NOT EXISTS "${prefix}/lib/rayform/librayform_mpi.so")
      message(FATAL_ERROR "not installed: ${prefix}/lib/rayform/librayform_mpi.so")
    endif()
    file(REMOVE "${WORK}/cli_mpi.png")
    # One machine, shared memory only (as tests/scripts/lib.sh's require_mpi).
    set(ENV{OMPI_MCA_btl} "self,vader")
    set(ENV{OMPI_MCA_pml} "ob1")
    set(ENV{OMPI_MCA_plm_rsh_agent} "")
    run(${mpirun} --allow-run-as-root --oversubscribe -np 2 "${prefix}/bin/rayform" render
        "${SOURCE_DIR}/scenes/default.txt" -o "${WORK}/cli_mpi.png" --size 32x24 --stats)
    if(NOT EXISTS "${WORK}/cli_mpi.png")
      message(FATAL_ERROR "the installed rayform under mpirun did not write ${WORK}/cli_mpi.png")
    endif()
  endif()

  run(${CMAKE_COMMAND} -S "${consumer_src}" -B "${WORK}/consumer" ${common} -DCMAKE_BUILD_TYPE=None
      "-DCMAKE_PREFIX_PATH=${prefix}" -DRAYFORM_CONSUMER_MODE=package)
  run(${CMAKE_COMMAND} --build "${WORK}/consumer" -j ${JOBS})
  check_render("${WORK}/consumer/consumer_render")

  # rayform.pc: the include folder, then the example compiled and linked with
  # pkg-config's flags alone.
  find_program(PKG_CONFIG pkg-config REQUIRED)
  set(ENV{PKG_CONFIG_PATH} "${prefix}/lib/pkgconfig")
  run(${PKG_CONFIG} --cflags --libs rayform)
  string(STRIP "${run_output}" flags)
  separate_arguments(flags UNIX_COMMAND "${flags}")
  set(found_include FALSE)
  foreach(f ${flags})
    if(f MATCHES "^-I(.*)")
      if(EXISTS "${CMAKE_MATCH_1}/rayform/importers/scene_io.h")
        set(found_include TRUE)
      endif()
    endif()
  endforeach()
  if(NOT found_include)
    message(FATAL_ERROR "pkg-config --cflags rayform names no folder holding rayform/importers/scene_io.h: ${flags}")
  endif()
  find_program(CXX NAMES c++ g++ REQUIRED)
  run(${CXX} -std=c++20 "${SOURCE_DIR}/examples/render_scene.cpp" -o "${WORK}/pc_render" ${flags})
  check_render("${WORK}/pc_render")
else()
  message(FATAL_ERROR "MODE is install or subdirectory, not '${MODE}'")
endif()
if(MODE STREQUAL "install")
  file(REMOVE_RECURSE "${WORK}")
endif()
string(TIMESTAMP finished "%s")
math(EXPR total "${finished} - ${started}")
message(STATUS "package.${MODE}: passed in ${total} s")
