/* Vector table and reset entry of the Cortex-M4F test program. Assembly, so that nothing runs
 * before the FPU is enabled: code compiled for the hard-float ABI may use the FPU anywhere, and
 * an FPU instruction while CP10/CP11 are disabled is a UsageFault. */
  .syntax unified
  .cpu cortex-m4
  .thumb

  .section .vectors, "a", %progbits
  .align 2
  .globl vectors
vectors:
  .word __stack_top      /* initial main stack pointer (linker script) */
  .word Reset_Handler
  .word Fault_Handler    /* NMI */
  .word Fault_Handler    /* HardFault */
  .word Fault_Handler    /* MemManage */
  .word Fault_Handler    /* BusFault */
  .word Fault_Handler    /* UsageFault */
  .word 0, 0, 0, 0       /* reserved */
  .word Fault_Handler    /* SVCall */
  .word Fault_Handler    /* DebugMonitor */
  .word 0                /* reserved */
  .word Fault_Handler    /* PendSV */
  .word Fault_Handler    /* SysTick */

  .text
  .align 1
  .globl Reset_Handler
  .thumb_func
  .type Reset_Handler, %function
Reset_Handler:
  /* CPACR (0xE000ED88) bits 20-23: full access to CP10 and CP11, the FPU (ARMv7-M ARM B3.2.20);
   * the barriers make the new access rights apply to the next instruction. */
  ldr r0, =0xE000ED88
  ldr r1, [r0]
  orr r1, r1, #(0xF << 20)
  str r1, [r0]
  dsb
  isb
  bl cortex_m4_start     /* start.c: memory, constructors, main, exit; does not return */
  b .
  .size Reset_Handler, . - Reset_Handler
  .ltorg
