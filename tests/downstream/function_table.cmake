# modelgen_generate() compiles exactly the files modelgen writes: the entry points it derives
# from modelgen's --list-functions, closed over what each calls, must be the function files of
# a real `modelgen --functions` run (its manifest), for every entry point alone and for a mix.
# Run by CTest: cmake -DMODELGEN=... -DMODELGEN_GENERATE=... -DROBOT=... -DWORK_DIR=...
#               -P function_table.cmake
include(${MODELGEN_GENERATE})
_modelgen_entry_points(entries ${MODELGEN})
set(names)
foreach(entry ${entries})
  string(REGEX REPLACE ":.*" "" name "${entry}")
  list(APPEND names ${name})
endforeach()
list(FIND names inverse_dynamics_identified identified)
list(FIND names drive_torque_state_jacobian state_jacobian)
if(identified EQUAL -1 OR state_jacobian EQUAL -1)
  message(FATAL_ERROR "modelgen --list-functions lacks known entry points: ${names}")
endif()
list(REMOVE_ITEM names inverse_dynamics_identified)  # needs --params
get_filename_component(stem ${ROBOT} NAME_WLE)
set(selections ${names} "mass_matrix_sincos,drive_torque_state_jacobian,energy_regressor")
foreach(selection ${selections})
  string(REPLACE "," ";" chosen "${selection}")
  _modelgen_needed_functions(expected "${entries}" "${chosen}" FALSE)
  file(REMOVE_RECURSE ${WORK_DIR})
  execute_process(COMMAND ${MODELGEN} ${ROBOT} -o ${WORK_DIR} --functions ${selection}
                  RESULT_VARIABLE result ERROR_VARIABLE errors OUTPUT_QUIET)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "modelgen --functions ${selection} failed (${result}): ${errors}")
  endif()
  file(READ ${WORK_DIR}/${stem}.json manifest)
  string(JSON count LENGTH "${manifest}" functions)
  set(written)
  math(EXPR last "${count} - 1")
  foreach(index RANGE ${last})
    string(JSON name GET "${manifest}" functions ${index} name)
    list(APPEND written ${name})
  endforeach()
  if(NOT written STREQUAL expected)
    message(FATAL_ERROR "--functions ${selection}: modelgen_generate() would compile "
                        "'${expected}', modelgen wrote '${written}'")
  endif()
endforeach()
list(LENGTH selections checked)
message(STATUS "modelgen_generate() compiles what modelgen writes (${checked} selections)")
