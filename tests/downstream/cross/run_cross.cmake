# Installs this build into a scratch prefix and builds tests/downstream/cross with the Cortex-M4F
# toolchain file against it: find_package(modelgen COMPONENTS generator) through modelgen_DIR,
# modelgen_generate(SCALAR float FUNCTIONS inverse_dynamics). Checks that the objects are ARM
# code, that only the chosen function was compiled, and that no double-precision routine
# (__aeabi_d*) was needed. Prints SKIPPED (CTest: skipped) when arm-none-eabi-g++ is missing.
# Run by CTest: cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -P run_cross.cmake
find_program(ARM_CXX arm-none-eabi-g++)
find_program(ARM_NM arm-none-eabi-nm)
if(NOT ARM_CXX OR NOT ARM_NM)
  message(STATUS "SKIPPED: arm-none-eabi-g++ not installed (Debian gcc-arm-none-eabi; .ci/setup "
                 "installs it)")
  return()
endif()
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGV}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/downstream/cross -B ${WORK_DIR}/build
    -DCMAKE_TOOLCHAIN_FILE=${SOURCE_DIR}/tests/downstream/cross/arm-none-eabi.cmake
    -Dmodelgen_DIR=${WORK_DIR}/prefix/lib/cmake/modelgen -DCMAKE_BUILD_TYPE=Release
    -DROBOT=${SOURCE_DIR}/robots/tx40.yaml)
if(NOT last_output MATCHES "runtime component refused: [^\n]*4-byte")
  message(FATAL_ERROR "the runtime component was not refused with the pointer sizes:\n${last_output}")
endif()
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
# The objects of the project's targets (CMakeFiles/<target>.dir/), not CMake's compiler probes.
file(GLOB_RECURSE objects ${WORK_DIR}/build/CMakeFiles/*.dir/*.o
     ${WORK_DIR}/build/CMakeFiles/*.dir/*.obj)
set(compiled)
foreach(object ${objects})
  get_filename_component(name ${object} NAME)
  string(REGEX REPLACE "\\.(o|obj)$" "" name "${name}")  # CMake names them .obj for Generic
  list(APPEND compiled ${name})
endforeach()
list(SORT compiled)
if(NOT compiled STREQUAL "controller.cpp;tx40.cpp;tx40_inverse_dynamics.cpp")
  message(FATAL_ERROR "expected the controller, the tables and inverse_dynamics only, got: ${compiled}")
endif()
run(${ARM_NM} -A ${objects})
if(last_output MATCHES "__aeabi_d[a-z0-9]*")
  message(FATAL_ERROR "double-precision routine ${CMAKE_MATCH_0} needed by the float build")
endif()
find_program(ARM_OBJDUMP arm-none-eabi-objdump)
run(${ARM_OBJDUMP} -f ${objects})
string(REGEX MATCHALL "file format [a-z0-9-]+" formats "${last_output}")
list(REMOVE_DUPLICATES formats)
if(NOT formats STREQUAL "file format elf32-littlearm")
  message(FATAL_ERROR "the objects are not all ARM code:\n${last_output}")
endif()
message(STATUS "cross build for Cortex-M4F: ${compiled}")
