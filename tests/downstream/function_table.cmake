# modelgen_generate() must know every file modelgen writes: its table of entry points
# (MODELGEN_ENTRY_POINTS) has to equal what the modelgen it runs lists (--list-functions), or a
# function added to the registry would be generated and never compiled.
# Run by CTest: cmake -DMODELGEN=... -DMODELGEN_GENERATE=... -P function_table.cmake
include(${MODELGEN_GENERATE})
execute_process(COMMAND ${MODELGEN} --list-functions
                RESULT_VARIABLE result OUTPUT_VARIABLE listed ERROR_VARIABLE errors)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "modelgen --list-functions failed (${result}): ${errors}")
endif()
string(REPLACE ";" "\n" table "${MODELGEN_ENTRY_POINTS}")
if(NOT listed STREQUAL "${table}\n")
  message(FATAL_ERROR "MODELGEN_ENTRY_POINTS in modelgen-generate.cmake differs from "
                      "modelgen --list-functions:\n--- table\n${table}\n--- modelgen\n${listed}")
endif()
message(STATUS "modelgen_generate() knows all entry points modelgen lists")
