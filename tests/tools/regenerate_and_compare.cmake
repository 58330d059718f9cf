# ctest -P script: run GENERATOR OUTPUT, then require OUTPUT == EXPECTED byte for byte.
execute_process(COMMAND ${GENERATOR} ${OUTPUT} RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${GENERATOR} failed with status ${status}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUTPUT} ${EXPECTED}
  RESULT_VARIABLE different)
if(different)
  message(FATAL_ERROR "${OUTPUT} differs from ${EXPECTED}: the sample capture is not "
                      "deterministic, or the generator changed without regenerating captures/")
endif()
message(STATUS "${OUTPUT} matches ${EXPECTED}")
