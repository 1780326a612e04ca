# Toolchain file for a bare-metal Cortex-M4F (single-precision FPU, hard-float ABI) with the GNU
# Arm Embedded toolchain and newlib (Debian: gcc-arm-none-eabi, libnewlib-arm-none-eabi).
# Written as a controller project's toolchain file would be: everything found must come from
# the target's root, so a host package is found only when pointed at explicitly
# (-Dmodelgen_DIR=...) and a host tool only through a cache variable (-DMODELGEN_EXECUTABLE=...).
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)

set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
# No program links without a linker script and startup code: check the compilers on a library.
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

set(cortex_m4f_flags "-mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16")
set(CMAKE_C_FLAGS_INIT "${cortex_m4f_flags}")
set(CMAKE_CXX_FLAGS_INIT "${cortex_m4f_flags} -fno-exceptions -fno-rtti")
set(CMAKE_ASM_FLAGS_INIT "${cortex_m4f_flags}")
# The flags select newlib's thumb/v7e-m+fp/hard multilib at link time too.
set(CMAKE_EXE_LINKER_FLAGS_INIT "${cortex_m4f_flags}")

# Search the target's root (the compiler's sysroot) for headers, libraries and packages; run
# programs from the host.
execute_process(COMMAND ${CMAKE_C_COMPILER} -print-sysroot
                OUTPUT_VARIABLE arm_sysroot OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT arm_sysroot)
  set(arm_sysroot /usr/lib/arm-none-eabi)
endif()
set(CMAKE_FIND_ROOT_PATH ${arm_sysroot})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
