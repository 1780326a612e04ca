# Installs this build into a scratch prefix, configures and builds tests/downstream against it
# (find_package(modelgen) + modelgen_generate), runs the consumer and checks what it prints.
# Run by CTest: cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DCXX_COMPILER=...
# [-DSANITIZER_FLAGS=...] -P run_downstream.cmake
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "failed: ${ARGV}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
# The consumer is built as this build was: the same compiler and, in a sanitized build, the same
# sanitizers, without which the installed libraries' sanitizer runtime does not link.
string(REPLACE ";" " " sanitizer_flags "${SANITIZER_FLAGS}")
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/downstream -B ${WORK_DIR}/build
    -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER} "-DCMAKE_CXX_FLAGS=${sanitizer_flags}"
    "-DCMAKE_EXE_LINKER_FLAGS=${sanitizer_flags}")
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/controller ${SOURCE_DIR}/robots/kr150.yaml)
# At q = 0 link 2 points along the base x axis and its joint axis z2 is the base y axis. A unit
# first moment along x under gravity (0, 0, -9.81) has moment (x, 0, 0) x (0, 0, -g) = (0, g, 0)
# about the joint: +9.81 N m about z2, so holding it takes tau2 = -9.81 N m; the reference
# dynamics of the description loaded at run time must agree to 1e-12.
if(NOT last_output MATCHES "^MX2 -9\\.810000 reference -9\\.810000 difference ([0-9.]+e-(1[2-9]|[2-9][0-9])|0\\.0e\\+00)")
  message(FATAL_ERROR "unexpected consumer output: '${last_output}'")
endif()
message(STATUS "downstream consumer printed: ${last_output}")

# The installed modelid on a description whose model the consumer built (LOADABLE), with no
# compiler to run: it must load that library (MODELGEN_MODEL_PATH) without a note and without
# compiling into its cache.
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env MODELGEN_MODEL_PATH=${WORK_DIR}/build
          CXX=${WORK_DIR}/no-such-compiler MODELGEN_CACHE_DIR=${WORK_DIR}/cache
          ${WORK_DIR}/prefix/bin/modelid design
          --robot ${SOURCE_DIR}/tests/model/loadable/puma560.yaml --period 5 --harmonics 2
          --starts 1 --max-evaluations 20 -o ${WORK_DIR}/design.yaml
  RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT result EQUAL 0 OR err MATCHES "note:" OR EXISTS ${WORK_DIR}/cache)
  message(FATAL_ERROR "modelid did not use the prebuilt model (exit ${result}):\n${err}")
endif()
message(STATUS "the installed modelid loaded the prebuilt puma560 model")
