#include "semihosting.h"

#include <stdint.h>

enum {
  kSysWrite0 = 0x04,
  kSysExitExtended = 0x20,
  kAdpStoppedApplicationExit = 0x20026,
};

/* Operation number in r0, argument (a pointer) in r1, result in r0. */
static int semihosting_call(int operation, const void* argument) {
  register int r0 __asm__("r0") = operation;
  register const void* r1 __asm__("r1") = argument;
  __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

void semihosting_write0(const char* text) { semihosting_call(kSysWrite0, text); }

void semihosting_exit(int status) {
  /* The AArch32 SYS_EXIT takes only a reason; the extended call also carries the status. */
  const uint32_t block[2] = {kAdpStoppedApplicationExit, (uint32_t)status};
  semihosting_call(kSysExitExtended, block);
  for (;;) {
  }
}
