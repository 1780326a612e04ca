# modelgen_generate(TARGET <name> ROBOT <description> [OUT_DIR <dir>] [SCALAR double|float|both]
#                   [PARAMS <EST.json>] [OPTIONS <modelgen options>...])
#
# Runs modelgen at build time on a robot description (MDH .yaml or .urdf) and defines a static
# library TARGET holding the generated code, with the output directory as its include path
# (#include "<stem>.hpp", namespace modelgen::<robot name>). Generation re-runs when the
# description, the estimate or modelgen changes; unchanged output is not rewritten, so nothing
# recompiles. PARAMS passes --params: the estimate's base parameters become the constants
# kIdentifiedBase and inverse_dynamics_identified uses them. It may be the OUTPUT of an
# add_custom_command of the same directory (a fit run at build time).
function(modelgen_generate)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "TARGET;ROBOT;OUT_DIR;SCALAR;PARAMS" "OPTIONS")
  if(arg_UNPARSED_ARGUMENTS)
    list(GET arg_UNPARSED_ARGUMENTS 0 unknown)
    message(FATAL_ERROR "modelgen_generate: unknown argument '${unknown}'")
  endif()
  foreach(required TARGET ROBOT)
    if(NOT arg_${required})
      message(FATAL_ERROR "modelgen_generate: ${required} is required")
    endif()
  endforeach()
  # list(FIND), not IN_LIST: the function may run where policy CMP0057 is not set.
  list(FIND arg_KEYWORDS_MISSING_VALUES PARAMS params_missing_value)
  if(NOT params_missing_value EQUAL -1)
    message(FATAL_ERROR "modelgen_generate: PARAMS needs an estimate file")
  endif()
  if(NOT arg_OUT_DIR)
    set(arg_OUT_DIR ${CMAKE_CURRENT_BINARY_DIR}/modelgen/${arg_TARGET})
  endif()
  if(NOT arg_SCALAR)
    set(arg_SCALAR both)
  endif()
  if(NOT arg_SCALAR MATCHES "^(double|float|both)$")
    message(FATAL_ERROR "modelgen_generate: SCALAR must be double, float or both, not '${arg_SCALAR}'")
  endif()
  get_filename_component(robot ${arg_ROBOT} ABSOLUTE)
  if(NOT EXISTS ${robot})
    message(FATAL_ERROR "modelgen_generate: ROBOT '${arg_ROBOT}' does not exist")
  endif()
  set(params_option)
  set(params_dependency)
  if(DEFINED arg_PARAMS)
    get_filename_component(params ${arg_PARAMS} ABSOLUTE)
    get_source_file_property(params_generated ${params} GENERATED)
    if(NOT EXISTS ${params} AND NOT params_generated)
      message(FATAL_ERROR "modelgen_generate: PARAMS '${arg_PARAMS}' does not exist and no "
                          "custom command of this directory makes it")
    endif()
    set(params_option --params ${params})
    set(params_dependency ${params})
  endif()
  # Output names follow the description's file stem, as on the modelgen command line.
  get_filename_component(stem ${robot} NAME_WLE)
  set(sources ${arg_OUT_DIR}/${stem}.hpp ${arg_OUT_DIR}/${stem}.cpp ${arg_OUT_DIR}/${stem}.json)
  set(stamp ${arg_OUT_DIR}/${stem}.stamp)
  add_custom_command(
    OUTPUT ${stamp}
    BYPRODUCTS ${sources}
    COMMAND modelgen::modelgen ${robot} -o ${arg_OUT_DIR} --scalar ${arg_SCALAR}
            ${params_option} ${arg_OPTIONS}
    COMMAND ${CMAKE_COMMAND} -E touch ${stamp}
    DEPENDS ${robot} ${params_dependency} $<TARGET_FILE:modelgen::modelgen>
    COMMENT "modelgen: generating ${stem} for ${arg_TARGET}"
    VERBATIM)
  add_library(${arg_TARGET} STATIC ${arg_OUT_DIR}/${stem}.cpp ${arg_OUT_DIR}/${stem}.hpp ${stamp})
  target_include_directories(${arg_TARGET} PUBLIC ${arg_OUT_DIR})
  target_compile_features(${arg_TARGET} PUBLIC cxx_std_11)
endfunction()
