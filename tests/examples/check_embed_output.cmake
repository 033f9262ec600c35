# Runs examples/embed.cpp's program (-DEXE=...) and checks what it prints: exit code 0 and
# one line "steps 100 min_det_F <value>" with 0 < value <= 1 (the square has landed and is
# compressed after 100 steps of `compress`, and no triangle inverted).
#   cmake -DEXE=build/release/examples/invfree_example_embed -P check_embed_output.cmake
execute_process(COMMAND "${EXE}" RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "embed example exited with ${status}: ${err}")
endif()
if(NOT out MATCHES "^steps ([0-9]+) min_det_F ([0-9]+\\.[0-9]+)\n$")
  message(FATAL_ERROR "embed example printed an unexpected line: '${out}'")
endif()
set(steps "${CMAKE_MATCH_1}")
set(min_det_f "${CMAKE_MATCH_2}")
if(NOT steps EQUAL 100)
  message(FATAL_ERROR "embed example took ${steps} steps, expected 100")
endif()
if(NOT min_det_f GREATER 0 OR min_det_f GREATER 1)
  message(FATAL_ERROR "embed example: min det F ${min_det_f} is outside (0, 1]")
endif()
message(STATUS "embed example: ${steps} steps, min det F ${min_det_f}")
