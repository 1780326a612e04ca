/* Arm semihosting (Semihosting for AArch32 and AArch64, v2.0): the program talks to the
 * debugger or emulator through `bkpt 0xab`. Only what the test program needs. */
#ifndef MODELGEN_CORTEX_M4_SEMIHOSTING_H_
#define MODELGEN_CORTEX_M4_SEMIHOSTING_H_

#ifdef __cplusplus
extern "C" {
#endif

/* SYS_WRITE0: writes a NUL-terminated string to the host's console. */
void semihosting_write0(const char* text);

/* SYS_EXIT_EXTENDED with ADP_Stopped_ApplicationExit: ends the emulation; qemu exits with
 * `status`. */
__attribute__((noreturn)) void semihosting_exit(int status);

#ifdef __cplusplus
}
#endif

#endif
