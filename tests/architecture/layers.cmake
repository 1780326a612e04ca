# The layering check (README, Layout): fails on any include or link that runs against the
# layers. Model core <- file formats <- generator; model core <- identification runtime <-
# experiment file formats <- modelid (which uses the file formats too).
#   cmake -DSOURCE_DIR=<tree> -P layers.cmake
# Each rule: the files of a layer, and the project include prefixes they may not use. Includes
# of a library's private headers (runtime/model/, runtime/src/) from another library are refused
# too, except the one listed in kAllowedPrivate.
cmake_minimum_required(VERSION 3.20)
if(NOT SOURCE_DIR)
  message(FATAL_ERROR "usage: cmake -DSOURCE_DIR=<tree> -P layers.cmake")
endif()

set(kRuntimeDomains "modelgen/(data|signal|excitation|estimation|ml|closed_loop)/")
# The position-reporting YAML reader of the model core (header only), shared with the experiment
# file formats so that their messages are positioned the same way as a description's.
set(kAllowedPrivate "runtime/model/yaml_reader.hpp")
set(kExperimentFormats "runtime/io/experiment/|runtime/include/modelgen/io/experiment/")

# layer name @ file globs (relative, separated by ',') @ refused include regex [@ files left out]
set(rules
  "model core@runtime/model/*.cpp,runtime/model/*.hpp,runtime/include/modelgen/model/*.hpp@^(modelgen/io/|${kRuntimeDomains}|generator/|runtime/cli/|runtime/src/|runtime/io/)"
  "file formats@runtime/io/*.cpp,runtime/include/modelgen/io/*.hpp@^(modelgen/io/experiment/|${kRuntimeDomains}|generator/|runtime/cli/|runtime/src/|runtime/model/)@^(${kExperimentFormats})"
  "experiment file formats@runtime/io/experiment/*.cpp,runtime/include/modelgen/io/experiment/*.hpp@^(generator/|runtime/cli/|runtime/src/|runtime/model/)"
  "generator@generator/*.cpp,generator/*.hpp@^(modelgen/io/experiment/|${kRuntimeDomains}|runtime/cli/|runtime/src/|runtime/model/|runtime/io/)"
  "identification runtime@runtime/src/*.cpp,runtime/src/*.hpp,runtime/include/modelgen/data/*.hpp,runtime/include/modelgen/signal/*.hpp,runtime/include/modelgen/excitation/*.hpp,runtime/include/modelgen/estimation/*.hpp,runtime/include/modelgen/ml/*.hpp,runtime/include/modelgen/closed_loop/*.hpp@^(modelgen/io/|generator/|runtime/cli/|runtime/model/|runtime/io/)"
  "modelid@runtime/cli/*.cpp,runtime/cli/*.hpp@^(generator/|runtime/src/|runtime/model/|runtime/io/)")

set(violations "")
set(checked 0)
foreach(rule ${rules})
  string(REPLACE "@" ";" parts "${rule}")
  list(GET parts 0 layer)
  list(GET parts 1 globs)
  list(GET parts 2 refused)
  list(LENGTH parts fields)
  string(REPLACE "," ";" globs "${globs}")
  set(files "")
  foreach(glob ${globs})
    file(GLOB_RECURSE found RELATIVE ${SOURCE_DIR} ${SOURCE_DIR}/${glob})
    list(APPEND files ${found})
  endforeach()
  if(fields GREATER 3)
    list(GET parts 3 left_out)
    list(FILTER files EXCLUDE REGEX "${left_out}")
  endif()
  foreach(source ${files})
    math(EXPR checked "${checked} + 1")
    file(STRINGS ${SOURCE_DIR}/${source} includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
    foreach(line ${includes})
      string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"]*)\".*" "\\1" header "${line}")
      if(header MATCHES "${refused}" AND NOT header STREQUAL "${kAllowedPrivate}")
        list(APPEND violations "${source}: the ${layer} includes \"${header}\"")
      endif()
    endforeach()
  endforeach()
endforeach()

# Links: the generator's libraries may name neither modelid's sources nor the runtime library.
if(EXISTS ${SOURCE_DIR}/generator/CMakeLists.txt)
  file(READ ${SOURCE_DIR}/generator/CMakeLists.txt generator_cmake)
  string(REGEX REPLACE "#[^\n]*" "" generator_cmake "${generator_cmake}")
  if(generator_cmake MATCHES "runtime/cli|runtime/src|modelgen_runtime|modelgen_design|modelgen_experiment_io")
    list(APPEND violations "generator/CMakeLists.txt: the generator compiles or links '${CMAKE_MATCH_0}'")
  endif()
endif()

if(violations)
  string(REPLACE ";" "\n  " text "${violations}")
  message(FATAL_ERROR "layering violations (README, Layout):\n  ${text}")
endif()
if(checked EQUAL 0)
  message(FATAL_ERROR "no source found under ${SOURCE_DIR}")
endif()
message(STATUS "layers: ${checked} files, no include or link against the layers")
