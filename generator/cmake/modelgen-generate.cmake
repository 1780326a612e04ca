# modelgen_generate(TARGET <name> ROBOT <description> [OUT_DIR <dir>]
#                   [SCALAR double|float|both] [FUNCTIONS <entry point>...] [PARAMS <EST.json>]
#                   [OPTIONS <modelgen options>...])
#
# Runs modelgen at build time on a robot description (MDH .yaml or .urdf) and defines a static
# library TARGET holding the generated code, with the output directory as its include path
# (#include "<stem>.hpp", namespace modelgen::<robot name>). Every entry point is a source file
# of its own (<stem>_<function>.cpp), so the library compiles in parallel and a firmware links
# only what it calls. FUNCTIONS keeps only those entry points and the ones they call (default:
# all). Generation re-runs when the description, the estimate or modelgen changes; unchanged
# output is not rewritten, so nothing recompiles. PARAMS passes --params: the estimate's base
# parameters become the constants kIdentifiedBase and inverse_dynamics_identified uses them. It
# may be the OUTPUT of an add_custom_command of the same directory (a fit run at build time).
# The generated sources are also listed in the variable <TARGET>_SOURCES of the caller.
#
# The generator is a host tool, as protoc is: in a cross build it runs on the build machine.
# It is the cache variable MODELGEN_EXECUTABLE when set (like Protobuf_PROTOC_EXECUTABLE),
# otherwise the imported target modelgen::modelgen of find_package(modelgen COMPONENTS
# generator), or the modelgen target of modelgen's own build. The generated code needs nothing
# from the package.

# Every entry point modelgen generates, in the order of its files, with the entry points each
# one needs after a colon ("modelgen --list-functions" prints the same; a test compares them,
# and modelgen_generate() compares them with a MODELGEN_EXECUTABLE or installed modelgen).
set(MODELGEN_ENTRY_POINTS
  idim_regressor_standard
  inverse_dynamics_standard
  joint_sincos
  idim_regressor_standard_sincos:joint_sincos
  inverse_dynamics_standard_sincos:joint_sincos
  base_from_standard
  idim_regressor
  inverse_dynamics
  mass_matrix
  idim_regressor_sincos:joint_sincos
  inverse_dynamics_sincos:joint_sincos
  mass_matrix_sincos:joint_sincos
  inverse_dynamics_state_jacobian
  energy_regressor
  power_regressor
  energy_regressor_sincos:joint_sincos
  power_regressor_sincos:joint_sincos
  drive_torque
  drive_torque_jacobian:idim_regressor_standard
  drive_torque_state_jacobian:base_from_standard,inverse_dynamics,inverse_dynamics_state_jacobian
  drive_regressor:idim_regressor_standard
  drive_torque_given_regressor
  drive_torque_jacobian_given_regressor
  inverse_dynamics_identified:inverse_dynamics)

set(MODELGEN_EXECUTABLE "" CACHE FILEPATH
    "The modelgen that modelgen_generate() runs (a build-machine executable in a cross build); \
empty: modelgen::modelgen")

# The entry points of MODELGEN_ENTRY_POINTS that `selection` needs (itself and what it calls,
# transitively), in file order; inverse_dynamics_identified only `with_params`.
function(_modelgen_needed_functions out selection with_params)
  set(names)
  foreach(entry ${MODELGEN_ENTRY_POINTS})
    string(REGEX REPLACE ":.*" "" name "${entry}")
    list(APPEND names ${name})
  endforeach()
  if(NOT with_params)
    list(REMOVE_ITEM names inverse_dynamics_identified)
  endif()
  if(NOT selection)
    set(${out} ${names} PARENT_SCOPE)
    return()
  endif()
  foreach(name ${selection})
    list(FIND names ${name} found)
    if(found EQUAL -1)
      if(name STREQUAL "inverse_dynamics_identified")
        message(FATAL_ERROR "modelgen_generate: FUNCTIONS inverse_dynamics_identified needs PARAMS")
      endif()
      string(REPLACE ";" ", " valid "${names}")
      message(FATAL_ERROR "modelgen_generate: FUNCTIONS: unknown function '${name}'; the "
                          "functions are: ${valid}")
    endif()
  endforeach()
  set(needed ${selection})
  set(pending ${selection})
  while(pending)
    list(POP_FRONT pending name)
    foreach(entry ${MODELGEN_ENTRY_POINTS})
      if(entry MATCHES "^${name}:(.*)$")
        string(REPLACE "," ";" callees "${CMAKE_MATCH_1}")
        foreach(callee ${callees})
          list(FIND needed ${callee} found)
          if(found EQUAL -1)
            list(APPEND needed ${callee})
            list(APPEND pending ${callee})
          endif()
        endforeach()
      endif()
    endforeach()
  endwhile()
  set(ordered)
  foreach(name ${names})
    list(FIND needed ${name} found)
    if(NOT found EQUAL -1)
      list(APPEND ordered ${name})
    endif()
  endforeach()
  set(${out} ${ordered} PARENT_SCOPE)
endfunction()

# Stops when the modelgen at `executable` generates other entry points than this file knows (a
# MODELGEN_EXECUTABLE of another version): its files would not be compiled, or not be there.
# Runs it once per executable and configure.
function(_modelgen_check_entry_points executable)
  string(MAKE_C_IDENTIFIER "${executable}" key)
  get_property(checked GLOBAL PROPERTY _modelgen_checked_${key})
  if(checked)
    return()
  endif()
  execute_process(COMMAND ${executable} --list-functions RESULT_VARIABLE result
                  OUTPUT_VARIABLE listed ERROR_VARIABLE errors)
  string(REPLACE ";" "\n" table "${MODELGEN_ENTRY_POINTS}")
  if(NOT result EQUAL 0 OR NOT listed STREQUAL "${table}\n")
    message(FATAL_ERROR "modelgen_generate: ${executable} does not generate the entry points "
                        "this modelgen_generate() knows (--list-functions: ${result}${errors}); use "
                        "the modelgen-generate.cmake installed with that modelgen")
  endif()
  set_property(GLOBAL PROPERTY _modelgen_checked_${key} TRUE)
endfunction()

function(modelgen_generate)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "TARGET;ROBOT;OUT_DIR;SCALAR;PARAMS"
                        "OPTIONS;FUNCTIONS")
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
  foreach(keyword PARAMS FUNCTIONS)
    list(FIND arg_KEYWORDS_MISSING_VALUES ${keyword} missing_value)
    if(NOT missing_value EQUAL -1)
      message(FATAL_ERROR "modelgen_generate: ${keyword} needs a value")
    endif()
  endforeach()
  # Options that decide which files are written have arguments of their own, which this
  # function turns into the library's sources.
  foreach(option ${arg_OPTIONS})
    foreach(pair "-o|OUT_DIR" "--output|OUT_DIR" "--scalar|SCALAR" "--params|PARAMS"
                 "--functions|FUNCTIONS")
      string(REPLACE "|" ";" pair "${pair}")
      list(GET pair 0 flag)
      list(GET pair 1 argument)
      if(option STREQUAL flag)
        message(FATAL_ERROR "modelgen_generate: give ${flag} as ${argument}, not in OPTIONS")
      endif()
    endforeach()
  endforeach()
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
  set(with_params FALSE)
  if(DEFINED arg_PARAMS)
    get_filename_component(params ${arg_PARAMS} ABSOLUTE)
    get_source_file_property(params_generated ${params} GENERATED)
    if(NOT EXISTS ${params} AND NOT params_generated)
      message(FATAL_ERROR "modelgen_generate: PARAMS '${arg_PARAMS}' does not exist and no "
                          "custom command of this directory makes it")
    endif()
    set(params_option --params ${params})
    set(params_dependency ${params})
    set(with_params TRUE)
  endif()
  _modelgen_needed_functions(functions "${arg_FUNCTIONS}" ${with_params})
  set(functions_option)
  if(arg_FUNCTIONS)
    string(REPLACE ";" "," functions_list "${arg_FUNCTIONS}")
    set(functions_option --functions ${functions_list})
  endif()
  if(MODELGEN_EXECUTABLE)
    if(NOT EXISTS "${MODELGEN_EXECUTABLE}")
      message(FATAL_ERROR "modelgen_generate: MODELGEN_EXECUTABLE '${MODELGEN_EXECUTABLE}' "
                          "does not exist")
    endif()
    set(generator ${MODELGEN_EXECUTABLE})
    set(generator_dependency ${MODELGEN_EXECUTABLE})
    _modelgen_check_entry_points(${MODELGEN_EXECUTABLE})
  elseif(TARGET modelgen::modelgen)
    set(generator modelgen::modelgen)
    set(generator_dependency $<TARGET_FILE:modelgen::modelgen>)
    # An installed modelgen can run now; the one of modelgen's own build is not built yet.
    get_target_property(imported modelgen::modelgen IMPORTED)
    if(imported)
      get_target_property(location modelgen::modelgen LOCATION)
      _modelgen_check_entry_points(${location})
    endif()
  else()
    message(FATAL_ERROR "modelgen_generate: no modelgen to run: find_package(modelgen "
                        "COMPONENTS generator) or set MODELGEN_EXECUTABLE to a modelgen that "
                        "runs on this machine")
  endif()
  # Output names follow the description's file stem, as on the modelgen command line.
  get_filename_component(stem ${robot} NAME_WLE)
  set(sources ${arg_OUT_DIR}/${stem}.cpp)
  foreach(function ${functions})
    list(APPEND sources ${arg_OUT_DIR}/${stem}_${function}.cpp)
  endforeach()
  set(stamp ${arg_OUT_DIR}/${stem}.stamp)
  # The arguments as a file the stamp depends on: changing FUNCTIONS, SCALAR or OPTIONS
  # re-runs modelgen with Make too (Ninja re-runs on a changed command by itself). Rewritten
  # only when they change.
  set(arguments_file ${CMAKE_CURRENT_BINARY_DIR}/modelgen/${arg_TARGET}.arguments)
  string(REPLACE ";" " " arguments
         "--scalar;${arg_SCALAR};${params_option};${functions_option};${arg_OPTIONS}")
  file(CONFIGURE OUTPUT ${arguments_file} CONTENT "${arguments}\n" @ONLY)
  add_custom_command(
    OUTPUT ${stamp}
    BYPRODUCTS ${sources} ${arg_OUT_DIR}/${stem}.hpp ${arg_OUT_DIR}/${stem}.json
    COMMAND ${generator} ${robot} -o ${arg_OUT_DIR} --scalar ${arg_SCALAR}
            ${params_option} ${functions_option} ${arg_OPTIONS}
    COMMAND ${CMAKE_COMMAND} -E touch ${stamp}
    DEPENDS ${robot} ${params_dependency} ${generator_dependency} ${arguments_file}
    COMMENT "modelgen: generating ${stem} for ${arg_TARGET}"
    VERBATIM)
  add_library(${arg_TARGET} STATIC ${sources} ${arg_OUT_DIR}/${stem}.hpp ${stamp})
  target_include_directories(${arg_TARGET} PUBLIC ${arg_OUT_DIR})
  target_compile_features(${arg_TARGET} PUBLIC cxx_std_11)
  set(${arg_TARGET}_SOURCES ${sources} PARENT_SCOPE)
endfunction()
