# Test of examples/render_scene.cpp (cmake -P): runs EXAMPLE on SCENE, then
# checks that OUTPUT is a PNG of WIDTH x HEIGHT pixels (read from its IHDR
# chunk: bytes 16-23 hold the width and height, big-endian).
foreach(v EXAMPLE SCENE OUTPUT WIDTH HEIGHT)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "check_render_scene.cmake needs -D${v}=...")
  endif()
endforeach()

file(REMOVE "${OUTPUT}")
execute_process(COMMAND "${EXAMPLE}" "${SCENE}" "${OUTPUT}" ${WIDTH} ${HEIGHT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "example exited with ${rc}:\n${out}${err}")
endif()
if(NOT EXISTS "${OUTPUT}")
  message(FATAL_ERROR "example did not write ${OUTPUT}")
endif()

file(READ "${OUTPUT}" signature LIMIT 8 HEX)
if(NOT signature STREQUAL "89504e470d0a1a0a")
  message(FATAL_ERROR "${OUTPUT} is not a PNG (starts with ${signature})")
endif()
file(READ "${OUTPUT}" w_hex OFFSET 16 LIMIT 4 HEX)
file(READ "${OUTPUT}" h_hex OFFSET 20 LIMIT 4 HEX)
math(EXPR w "0x${w_hex}")
math(EXPR h "0x${h_hex}")
if(NOT w EQUAL WIDTH OR NOT h EQUAL HEIGHT)
  message(FATAL_ERROR "${OUTPUT} is ${w}x${h}, expected ${WIDTH}x${HEIGHT}")
endif()
file(REMOVE "${OUTPUT}")
message(STATUS "example wrote a ${w}x${h} PNG")
