/* Start-up for the C test program on QEMU `virt` (RV32IMC, no FPU): the stack, .bss, run(), then
 * a semihosting exit with run()'s status. */
#include <stdint.h>

extern int run(void);
extern uint32_t _sbss, _ebss;

static void semihosting_exit(int ok) {
    /* SYS_EXIT (0x18); ADP_Stopped_ApplicationExit (0x20026) exits QEMU with status 0 */
    register long a0 __asm__("a0") = 0x18;
    register long a1 __asm__("a1") = ok ? 0x20026 : 0x20023;
    __asm__ volatile(".option push\n.option norvc\n"
                     "slli x0, x0, 0x1f\nebreak\nsrai x0, x0, 7\n.option pop"
                     : "+r"(a0) : "r"(a1) : "memory");
    for (;;) {}
}

void start_c(void) {
    for (uint32_t *p = &_sbss; p < &_ebss;) *p++ = 0;
    semihosting_exit(run() == 0);
}

__attribute__((naked, section(".text.start"))) void _start(void) {
    __asm__ volatile("la sp, _estack\n j start_c");
}
