# The emulated-controller test: cross-builds this folder's program for a Cortex-M4F with a float
# TX-40 from modelgen_generate(), fails on any soft-double routine in it, runs it on qemu's
# mps2-an386 and compares what it prints with the host double model (host_reference.cpp).
# Reports code size and stack use per generated function. Run by CTest:
#   cmake -DMODELGEN=<host modelgen> -DHOST_REFERENCE=<cortex_m4_host_reference>
#         -DWORK_DIR=<scratch dir> [-DSCALAR=both] -P run_m4.cmake
# SCALAR=both (by hand) builds the program with the double code too: the soft-double check must
# then fail. Skipped (a line CTest's SKIP_REGULAR_EXPRESSION matches) when none of the tools is
# installed; any one missing is an error.
foreach(required MODELGEN HOST_REFERENCE WORK_DIR)
  if(NOT ${required})
    message(FATAL_ERROR "run_m4.cmake: -D${required}=... is required")
  endif()
endforeach()
set(source_dir ${CMAKE_CURRENT_LIST_DIR})
set(build_dir ${WORK_DIR}/build)
set(packages "gcc-arm-none-eabi libnewlib-arm-none-eabi libstdc++-arm-none-eabi-dev qemu-system-arm")

# --- The tools: all or none.
set(tools arm-none-eabi-gcc arm-none-eabi-g++ arm-none-eabi-nm arm-none-eabi-size qemu-system-arm)
set(found)
set(missing)
foreach(tool ${tools})
  find_program(${tool}_path ${tool})
  if(${tool}_path)
    list(APPEND found ${tool})
  else()
    list(APPEND missing ${tool})
  endif()
endforeach()
if(NOT found)
  message(STATUS "cortex_m4 test SKIPPED: no Arm cross compiler and no qemu-system-arm on PATH "
                 "(Debian: apt-get install ${packages}; CI installs them)")
  return()
endif()
if(missing)
  string(REPLACE ";" ", " missing "${missing}")
  message(FATAL_ERROR "cortex_m4 test: ${missing} not found on PATH, though other tools of the "
                      "test are; install ${packages}")
endif()
set(cpu_flags -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16)
execute_process(COMMAND ${arm-none-eabi-gcc_path} ${cpu_flags} -print-file-name=libm.a
                OUTPUT_VARIABLE libm OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT IS_ABSOLUTE "${libm}" OR NOT EXISTS "${libm}")
  message(FATAL_ERROR "cortex_m4 test: arm-none-eabi-gcc has no newlib libm.a for the "
                      "Cortex-M4F (${cpu_flags}); install libnewlib-arm-none-eabi")
endif()
file(MAKE_DIRECTORY ${WORK_DIR})
file(WRITE ${WORK_DIR}/cmath_probe.cpp "#include <cmath>\nfloat f(float x) { return std::sin(x); }\n")
execute_process(COMMAND ${arm-none-eabi-g++_path} ${cpu_flags} -fsyntax-only
                        ${WORK_DIR}/cmath_probe.cpp
                RESULT_VARIABLE probe_result ERROR_VARIABLE probe_error)
if(NOT probe_result EQUAL 0)
  message(FATAL_ERROR "cortex_m4 test: arm-none-eabi-g++ has no C++ headers (<cmath>); install "
                      "libstdc++-arm-none-eabi-dev\n${probe_error}")
endif()

function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "cortex_m4 test: failed: ${ARGV}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()

# --- Cross build: the toolchain file as a controller project has it, the host modelgen through
# the cache variable.
set(scalar_option)
if(SCALAR)
  set(scalar_option -DMODELGEN_SCALAR=${SCALAR})
endif()
# Host compiler flags from the environment (a sanitizer build's, say) are not the target's.
file(REMOVE_RECURSE ${build_dir})
run(${CMAKE_COMMAND} -E env --unset=CFLAGS --unset=CXXFLAGS --unset=ASMFLAGS --unset=LDFLAGS
    ${CMAKE_COMMAND} -S ${source_dir} -B ${build_dir}
    -DCMAKE_TOOLCHAIN_FILE=${source_dir}/arm-none-eabi.cmake -DMODELGEN_EXECUTABLE=${MODELGEN}
    ${scalar_option})
run(${CMAKE_COMMAND} --build ${build_dir} --parallel 2)
set(elf ${build_dir}/cortex_m4_tx40.elf)

# --- No soft double: the AEABI double routines (__aeabi_dadd, __aeabi_f2d, ...) and libgcc's
# names for them (__adddf3, __extendsfdf2, ...), defined or referenced.
function(soft_double_symbols out nm_output)
  string(REPLACE "\n" ";" lines "${nm_output}")
  set(names)
  foreach(line ${lines})
    if(line MATCHES " (__aeabi_d[a-z0-9]+|__aeabi_[a-z0-9]+2d|__[a-z]+df[a-z0-9]*)$")
      list(APPEND names ${CMAKE_MATCH_1})
    endif()
  endforeach()
  list(REMOVE_DUPLICATES names)
  string(REPLACE ";" " " names "${names}")
  set(${out} "${names}" PARENT_SCOPE)
endfunction()
# The check must see one double multiplication and one float-to-double promotion.
file(WRITE ${WORK_DIR}/double_probe.c "double f(float a, double b) { return a * b; }\n")
run(${arm-none-eabi-gcc_path} ${cpu_flags} -O2 -c ${WORK_DIR}/double_probe.c
    -o ${WORK_DIR}/double_probe.o)
run(${arm-none-eabi-nm_path} ${WORK_DIR}/double_probe.o)
soft_double_symbols(probe_symbols "${last_output}")
if(NOT probe_symbols MATCHES "__aeabi_dmul" OR NOT probe_symbols MATCHES "__aeabi_f2d")
  message(FATAL_ERROR "cortex_m4 test: the soft-double check finds '${probe_symbols}' in a "
                      "double multiplication, not __aeabi_dmul and __aeabi_f2d:\n${last_output}")
endif()
run(${arm-none-eabi-nm_path} ${elf})
set(symbols "${last_output}")
soft_double_symbols(soft_double "${symbols}")
if(soft_double)
  message(FATAL_ERROR "cortex_m4 test: the float-only program contains soft-double routines: "
                      "${soft_double}\n(something computes in double on a single-precision FPU; "
                      "arm-none-eabi-nm ${elf})")
endif()

# --- Run on the emulated board; semihosting writes to qemu's stderr, both go to one file.
set(output ${WORK_DIR}/qemu_output.txt)
string(TIMESTAMP started "%s.%f")
execute_process(
  COMMAND ${qemu-system-arm_path} -M mps2-an386 -nographic
          -semihosting-config enable=on,target=native -kernel ${elf}
  TIMEOUT 60 RESULT_VARIABLE qemu_result OUTPUT_FILE ${output} ERROR_FILE ${output})
string(TIMESTAMP finished "%s.%f")
file(READ ${output} printed)
if(NOT qemu_result EQUAL 0)
  string(LENGTH "${printed}" length)
  if(length GREATER 2000)
    math(EXPR from "${length} - 2000")
    string(SUBSTRING "${printed}" ${from} -1 printed)
  endif()
  message(FATAL_ERROR "cortex_m4 test: qemu-system-arm -M mps2-an386 ended with '${qemu_result}' "
                      "(0 is main returning 0, 3 a fault); its output ends:\n${printed}")
endif()
# Seconds to milliseconds without floating point: CMake's math() is integer only.
string(REGEX REPLACE "^([0-9]+)\\.([0-9][0-9][0-9]).*" "\\1\\2" started_ms ${started})
string(REGEX REPLACE "^([0-9]+)\\.([0-9][0-9][0-9]).*" "\\1\\2" finished_ms ${finished})
math(EXPR qemu_ms "${finished_ms} - ${started_ms}")

# --- Compare with the host double model.
execute_process(COMMAND ${HOST_REFERENCE} ${output} RESULT_VARIABLE compare_result
                OUTPUT_VARIABLE comparison ERROR_VARIABLE comparison)
if(NOT compare_result EQUAL 0)
  message(FATAL_ERROR "cortex_m4 test: the target's float results differ from the host double "
                      "model (${output}):\n${comparison}")
endif()

# --- Code size per generated function (its object in the library, as linked without section
# garbage collection) and stack use (GCC's -fstack-usage for the function alone; measured on
# the target for the call, sinf/cosf included).
run(${arm-none-eabi-size_path} ${build_dir}/libtx40_m4.a)
string(REPLACE "\n" ";" size_lines "${last_output}")
file(GLOB_RECURSE stack_files ${build_dir}/*.su)
set(stack_text)
foreach(stack_file ${stack_files})
  file(READ ${stack_file} text)
  string(APPEND stack_text "${text}")
endforeach()
string(REPLACE ";" " " cpu_text "${cpu_flags}")
message(STATUS "cortex_m4: TX-40 float, ${cpu_text}, -O2, qemu mps2-an386 run ${qemu_ms} ms")
string(REPLACE "\n" "\n-- cortex_m4: " comparison "${comparison}")
string(REGEX REPLACE "\n-- cortex_m4: $" "" comparison "${comparison}")
message(STATUS "cortex_m4: ${comparison}")
# Left-justified columns for the table below.
function(padded out text width)
  string(LENGTH "${text}" length)
  if(length LESS width)
    math(EXPR fill "${width} - ${length}")
    string(REPEAT " " ${fill} spaces)
    string(APPEND text "${spaces}")
  endif()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()
padded(header "function" 20)
message(STATUS "cortex_m4: ${header}code B  stack B (.su)  stack B (measured, with sinf/cosf)")
foreach(line ${size_lines})
  if(line MATCHES "^[ \t]*([0-9]+)[ \t]+([0-9]+)[ \t]+([0-9]+)[ \t].*tx40_?([a-z_]*)\\.cpp\\.obj")
    set(function ${CMAKE_MATCH_4})
    math(EXPR code "${CMAKE_MATCH_1} + ${CMAKE_MATCH_2}")
    set(su "-")
    set(measured "-")
    if(function)
      if(stack_text MATCHES "modelgen::tx40::${function}\\(const float[^\t]*\t([0-9]+)")
        set(su ${CMAKE_MATCH_1})
      endif()
      if(printed MATCHES "stack ${function} ([0-9]+)")
        set(measured ${CMAKE_MATCH_1})
      endif()
    elseif(symbols MATCHES "kBaseParamNames")
      set(function "tables (linked)")
    else()
      set(function "tables (not linked)")
    endif()
    padded(function "${function}" 20)
    padded(code "${code}" 8)
    padded(su "${su}" 15)
    message(STATUS "cortex_m4: ${function}${code}${su}${measured}")
  endif()
endforeach()
run(${arm-none-eabi-size_path} ${elf})
string(REGEX MATCH "\n[ \t]*([0-9]+)[ \t]+([0-9]+)[ \t]+([0-9]+)" totals "${last_output}")
message(STATUS "cortex_m4: whole program (model, libm sinf/cosf, startup, output): "
               "text ${CMAKE_MATCH_1} B, data ${CMAKE_MATCH_2} B, bss ${CMAKE_MATCH_3} B")
