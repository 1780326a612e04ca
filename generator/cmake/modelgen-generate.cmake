# modelgen_generate(TARGET <name> ROBOT <description> [OUT_DIR <dir>]
#                   [SCALAR double|float|both] [FUNCTIONS <entry point>...] [PARAMS <EST.json>]
#                   [LOADABLE] [OPTIONS <modelgen options>...])
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
# LOADABLE makes TARGET a shared library (MODULE) with modelgen --loadable's C entry point
# instead: the model modelid loads for this description without compiling anything at run time,
# when the library is in a folder of $MODELGEN_MODEL_PATH or installed into
# <prefix>/lib/modelgen/models (docs/compiled-models.md). It needs every function, so it takes
# no FUNCTIONS.
#
# The generator is a host tool, as protoc is: in a cross build it runs on the build machine.
# It is the cache variable MODELGEN_EXECUTABLE when set (like Protobuf_PROTOC_EXECUTABLE),
# otherwise the imported target modelgen::modelgen of find_package(modelgen COMPONENTS
# generator), or the modelgen target of modelgen's own build. The generated code needs nothing
# from the package. Which files modelgen writes comes from modelgen itself (--list-functions,
# its registry of generated functions), asked at configure time; the modelgen target of the
# same build cannot be asked yet, so there the entry points compile as one source that includes
# those the manifest lists.

set(MODELGEN_EXECUTABLE "" CACHE FILEPATH
    "The modelgen that modelgen_generate() runs (a build-machine executable in a cross build); \
empty: modelgen::modelgen")

# The entry points the modelgen at `executable` writes, in the order of its files, each with
# the entry points it needs after a colon ("name:callee,callee"): its --list-functions, which
# prints its registry of generated functions. Asked once per executable and configure.
function(_modelgen_entry_points out executable)
  string(MAKE_C_IDENTIFIER "${executable}" key)
  get_property(known GLOBAL PROPERTY _modelgen_entry_points_${key} SET)
  if(NOT known)
    execute_process(COMMAND ${executable} --list-functions RESULT_VARIABLE result
                    OUTPUT_VARIABLE listed ERROR_VARIABLE errors)
    if(NOT result EQUAL 0 OR listed STREQUAL "")
      message(FATAL_ERROR "modelgen_generate: ${executable} --list-functions failed "
                          "(${result}): ${errors}")
    endif()
    string(STRIP "${listed}" listed)
    string(REPLACE "\n" ";" listed "${listed}")
    set_property(GLOBAL PROPERTY _modelgen_entry_points_${key} "${listed}")
  endif()
  get_property(entries GLOBAL PROPERTY _modelgen_entry_points_${key})
  set(${out} ${entries} PARENT_SCOPE)
endfunction()

# The entry points of `entries` (as _modelgen_entry_points gives them) that `selection` needs
# (itself and what it calls, transitively), in file order; inverse_dynamics_identified only
# `with_params`.
function(_modelgen_needed_functions out entries selection with_params)
  set(names)
  foreach(entry ${entries})
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
    foreach(entry ${entries})
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

function(modelgen_generate)
  cmake_parse_arguments(PARSE_ARGV 0 arg "LOADABLE" "TARGET;ROBOT;OUT_DIR;SCALAR;PARAMS"
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
                 "--functions|FUNCTIONS" "--loadable|LOADABLE")
      string(REPLACE "|" ";" pair "${pair}")
      list(GET pair 0 flag)
      list(GET pair 1 argument)
      if(option STREQUAL flag)
        message(FATAL_ERROR "modelgen_generate: give ${flag} as ${argument}, not in OPTIONS")
      endif()
    endforeach()
  endforeach()
  if(arg_LOADABLE AND arg_FUNCTIONS)
    message(FATAL_ERROR "modelgen_generate: LOADABLE takes every function, not FUNCTIONS")
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
  set(loadable_option)
  if(arg_LOADABLE)
    set(loadable_option --loadable)
  endif()
  set(functions_option)
  if(arg_FUNCTIONS)
    string(REPLACE ";" "," functions_list "${arg_FUNCTIONS}")
    set(functions_option --functions ${functions_list})
  endif()
  # The generator, and the modelgen whose --list-functions says which files it writes: one that
  # runs now (MODELGEN_EXECUTABLE, an installed modelgen::modelgen), or none for the modelgen
  # target of this build, which is not built yet.
  set(lister)
  if(MODELGEN_EXECUTABLE)
    if(NOT EXISTS "${MODELGEN_EXECUTABLE}")
      message(FATAL_ERROR "modelgen_generate: MODELGEN_EXECUTABLE '${MODELGEN_EXECUTABLE}' "
                          "does not exist")
    endif()
    set(generator ${MODELGEN_EXECUTABLE})
    set(generator_dependency ${MODELGEN_EXECUTABLE})
    set(lister ${MODELGEN_EXECUTABLE})
  elseif(TARGET modelgen::modelgen)
    set(generator modelgen::modelgen)
    set(generator_dependency $<TARGET_FILE:modelgen::modelgen>)
    get_target_property(imported modelgen::modelgen IMPORTED)
    if(imported)
      get_target_property(lister modelgen::modelgen LOCATION)
    endif()
  else()
    message(FATAL_ERROR "modelgen_generate: no modelgen to run: find_package(modelgen "
                        "COMPONENTS generator) or set MODELGEN_EXECUTABLE to a modelgen that "
                        "runs on this machine")
  endif()
  # Output names follow the description's file stem, as on the modelgen command line.
  get_filename_component(stem ${robot} NAME_WLE)
  set(sources ${arg_OUT_DIR}/${stem}.cpp)
  set(collect_command)
  if(lister)
    # A source per entry point: the library compiles in parallel, a firmware links what it calls.
    _modelgen_entry_points(entries ${lister})
    _modelgen_needed_functions(functions "${entries}" "${arg_FUNCTIONS}" ${with_params})
    foreach(function ${functions})
      list(APPEND sources ${arg_OUT_DIR}/${stem}_${function}.cpp)
    endforeach()
    if(arg_LOADABLE)
      list(APPEND sources ${arg_OUT_DIR}/${stem}_loadable.cpp)
    endif()
  else()
    # Which files the generator writes is known once it ran: one source includes the entry
    # points its manifest lists (modelgen checks FUNCTIONS itself).
    set(collector ${CMAKE_CURRENT_BINARY_DIR}/modelgen/collect_entry_points.cmake)
    file(CONFIGURE OUTPUT ${collector} CONTENT [=[
file(READ ${MANIFEST} manifest)
string(JSON count LENGTH "${manifest}" files)
set(text "// Generated by modelgen_generate(): every entry point ${STEM}.json lists.\n")
math(EXPR last "${count} - 1")
foreach(index RANGE ${last})
  string(JSON file GET "${manifest}" files ${index})
  if(file MATCHES "^${STEM}_.*\\.cpp$")
    string(APPEND text "#include \"${file}\"\n")
  endif()
endforeach()
file(CONFIGURE OUTPUT ${OUTPUT} CONTENT "${text}")
]=] @ONLY)
    set(collected ${arg_OUT_DIR}/${stem}_entry_points.cpp)
    list(APPEND sources ${collected})
    set(collect_command COMMAND ${CMAKE_COMMAND} -DMANIFEST=${arg_OUT_DIR}/${stem}.json
                        -DSTEM=${stem} -DOUTPUT=${collected} -P ${collector})
  endif()
  set(stamp ${arg_OUT_DIR}/${stem}.stamp)
  # The arguments as a file the stamp depends on: changing FUNCTIONS, SCALAR or OPTIONS
  # re-runs modelgen with Make too (Ninja re-runs on a changed command by itself). Rewritten
  # only when they change.
  set(arguments_file ${CMAKE_CURRENT_BINARY_DIR}/modelgen/${arg_TARGET}.arguments)
  string(REPLACE ";" " " arguments
         "--scalar;${arg_SCALAR};${params_option};${functions_option};${loadable_option};${arg_OPTIONS}")
  file(CONFIGURE OUTPUT ${arguments_file} CONTENT "${arguments}\n" @ONLY)
  add_custom_command(
    OUTPUT ${stamp}
    BYPRODUCTS ${sources} ${arg_OUT_DIR}/${stem}.hpp ${arg_OUT_DIR}/${stem}.json
    COMMAND ${generator} ${robot} -o ${arg_OUT_DIR} --scalar ${arg_SCALAR}
            ${params_option} ${functions_option} ${loadable_option} ${arg_OPTIONS}
    ${collect_command}
    COMMAND ${CMAKE_COMMAND} -E touch ${stamp}
    DEPENDS ${robot} ${params_dependency} ${generator_dependency} ${arguments_file}
    COMMENT "modelgen: generating ${stem} for ${arg_TARGET}"
    VERBATIM)
  if(arg_LOADABLE)
    add_library(${arg_TARGET} MODULE ${sources} ${arg_OUT_DIR}/${stem}.hpp ${stamp})
  else()
    add_library(${arg_TARGET} STATIC ${sources} ${arg_OUT_DIR}/${stem}.hpp ${stamp})
  endif()
  target_include_directories(${arg_TARGET} PUBLIC ${arg_OUT_DIR})
  target_compile_features(${arg_TARGET} PUBLIC cxx_std_11)
  set(${arg_TARGET}_SOURCES ${sources} PARENT_SCOPE)
endfunction()
