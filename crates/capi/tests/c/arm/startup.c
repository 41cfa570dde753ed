/* Start-up for the C test program on QEMU mps2-an386: the vector table, .data and .bss, the FPU
 * on, run(), then a semihosting exit with run()'s status (a fault exits with status 1). */
#include <stdint.h>

extern int run(void);
extern uint32_t _estack, _sidata, _sdata, _edata, _sbss, _ebss;

static void semihosting_exit(int ok) {
    /* SYS_EXIT (0x18); ADP_Stopped_ApplicationExit (0x20026) exits QEMU with status 0,
       ADP_Stopped_RunTimeErrorUnknown (0x20023) with status 1 */
    register int r0 __asm__("r0") = 0x18;
    register int r1 __asm__("r1") = ok ? 0x20026 : 0x20023;
    __asm__ volatile("bkpt 0xab" : : "r"(r0), "r"(r1) : "memory");
    for (;;) {}
}

void reset(void) {
    uint32_t *src = &_sidata, *dst = &_sdata;
    while (dst < &_edata) *dst++ = *src++;
    for (dst = &_sbss; dst < &_ebss;) *dst++ = 0;
    /* CPACR: full access to CP10 and CP11 (the FPU) */
    *(volatile uint32_t *)0xE000ED88 |= 0xFu << 20;
    __asm__ volatile("dsb\n isb");
    semihosting_exit(run() == 0);
}

static void fault(void) { semihosting_exit(0); }

__attribute__((section(".vectors"), used)) static const void *const vectors[16] = {
    &_estack, (const void *)reset, (const void *)fault, (const void *)fault,
    (const void *)fault, (const void *)fault, (const void *)fault,
};
