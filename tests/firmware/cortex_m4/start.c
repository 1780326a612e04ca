/* C part of the reset sequence (startup.S enabled the FPU): RAM initialised as the C and C++
 * languages require, then main, whose result ends the emulation. */
#include <stdint.h>
#include <string.h>

#include "semihosting.h"

/* From the linker script (mps2_an386.ld). */
extern uint32_t __data_load[], __data_start[], __data_end[], __bss_start[], __bss_end[];
extern void (*__init_array_start[])(void);
extern void (*__init_array_end[])(void);

int main(void);

void cortex_m4_start(void) {
  memcpy(__data_start, __data_load, (size_t)((char*)__data_end - (char*)__data_start));
  memset(__bss_start, 0, (size_t)((char*)__bss_end - (char*)__bss_start));
  for (void (**constructor)(void) = __init_array_start; constructor != __init_array_end;
       ++constructor) {
    (*constructor)();
  }
  semihosting_exit(main());
}

/* Any fault or unexpected exception: say so and stop, rather than hang until the timeout. */
void Fault_Handler(void) {
  semihosting_write0("fault: exception taken, stopping\n");
  semihosting_exit(3);
}
