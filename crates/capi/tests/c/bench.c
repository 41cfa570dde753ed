/* Instructions per call under QEMU with `-icount shift=0` (1 ns of virtual time per
 * instruction): each call repeated and the timer's difference averaged. On mps2-an386 the timer
 * is SysTick at 25 MHz (one tick per 40 instructions), on RISC-V `virt` the CLINT's mtime at
 * 10 MHz (one per 100). Stack per call: 32 KiB below the caller painted, the call made once,
 * the deepest word written found (`stack NAME BYTES`). Build and run as docs/performance.md
 * ("C library") says; with -DGROUP=n only one function group is called (code size per group).
 * Needs `calibration_blob.h` (written by the test `c_program::*` into
 * target/capi-c/TARGET/) on the include path. */
#include "specpoly.h"
#include <stdint.h>

#include "calibration_blob.h"
#include "spectra_samples.h"

#if defined(__arm__)
#define SYST_CSR (*(volatile uint32_t *)0xE000E010)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018)
#define PER_TICK 40u
static void out(const char *s) {
    register int r0 __asm__("r0") = 0x04;
    register const char *r1 __asm__("r1") = s;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
}
static uint32_t start(void) { SYST_RVR = 0xFFFFFF; SYST_CVR = 0; SYST_CSR = 5; return SYST_CVR; }
static uint32_t since(uint32_t t0) { return (t0 - SYST_CVR) & 0xFFFFFF; }
#elif defined(__riscv)
#define MTIME (*(volatile uint32_t *)0x0200BFF8)
#define PER_TICK 100u
static void out(const char *s) {
    register long a0 __asm__("a0") = 0x04;
    register const char *a1 __asm__("a1") = s;
    __asm__ volatile(".option push\n.option norvc\n"
                     "slli x0, x0, 0x1f\nebreak\nsrai x0, x0, 7\n.option pop"
                     : "+r"(a0) : "r"(a1) : "memory");
}
static uint32_t start(void) { return MTIME; }
static uint32_t since(uint32_t t0) { return MTIME - t0; }
#endif

static void report(const char *name, uint32_t ticks, uint32_t n) {
    char b[64], *p = b;
    while (*name) *p++ = *name++;
    *p++ = ' ';
    uint32_t v = (uint32_t)((uint64_t)ticks * PER_TICK * 10u / n); /* tenths of an instruction */
    char d[12];
    int i = 0;
    do { d[i++] = (char)('0' + v % 10); v /= 10; } while (v);
    if (i == 1) d[i++] = '0';
    while (i > 1) *p++ = d[--i];
    *p++ = '.';
    *p++ = d[0];
    *p++ = '\n';
    *p = 0;
    out(b);
}

volatile float sink;

/* stack depth: paint below the caller's frame, call, find the deepest word written */
#define PAINT 32768u
#define MARK 0xA5C3E1F7u
static uintptr_t sp_now(void) {
    uintptr_t s;
#if defined(__arm__)
    __asm__ volatile("mov %0, sp" : "=r"(s));
#else
    __asm__ volatile("mv %0, sp" : "=r"(s));
#endif
    return s;
}
static uintptr_t top;
__attribute__((noinline)) static void paint(void) {
    for (volatile uint32_t *p = (uint32_t *)(top - PAINT); p < (uint32_t *)top; p++) *p = MARK;
}
__attribute__((noinline)) static void stack_report(const char *name) {
    volatile uint32_t *p = (uint32_t *)(top - PAINT);
    while (p < (uint32_t *)top && *p == MARK) p++;
    char b[64], *q = b;
    while (*name) *q++ = *name++;
    const char *w = " stack ";
    while (*w) *q++ = *w++;
    uint32_t v = (uint32_t)(top + 64 - (uintptr_t)p), i = 0; /* bytes below the caller's sp */
    char d[12];
    do { d[i++] = (char)('0' + v % 10); v /= 10; } while (v);
    while (i) *q++ = d[--i];
    *q++ = '\n';
    *q = 0;
    out(b);
}
#define STACK(name, call) do { paint(); call; stack_report(name); } while (0)

int run(void) {
    SpMixer m;
    sp_mixer_init(&m);
    static const float xyz[4][3] = {
        {0.65f, 0.30f, 0.0f}, {0.25f, 0.70f, 0.10f}, {0.18f, 0.08f, 0.95f}, {0.95f, 1.0f, 0.85f},
    };
    m.count = 4;
    for (int i = 0; i < 4; i++) {
        __builtin_memcpy(m.channels[i].xyz, xyz[i], sizeof xyz[i]);
        m.channels[i].cost = 1.0f;
        m.channels[i].gamma = 1.0f;
    }
    uint32_t t;
    top = sp_now() - 64;
#if !defined(GROUP) || GROUP == 1
    SpXy xy;
    t = start();
    for (int i = 0; i < 100; i++) sp_cct_to_xy(2700.0f + (float)i, 0.001f, &xy);
    report("sp_cct_to_xy", since(t), 100);
    STACK("sp_cct_to_xy", sp_cct_to_xy(2700.0f, 0.001f, &xy));
    sink = xy.x;
#endif
#if !defined(GROUP) || GROUP == 2
    SpCct c;
    t = start();
    for (int i = 0; i < 4; i++) sp_xy_to_cct(0.3127 + 0.001 * i, 0.329, &c);
    report("sp_xy_to_cct", since(t), 4);
    STACK("sp_xy_to_cct", sp_xy_to_cct(0.3127, 0.329, &c));
    sink = (float)c.cct;
#endif
#if !defined(GROUP) || GROUP == 3
    SpMixResult r;
    SpMixStep s;
    m.fade_ms = 0;
    t = start();
    for (int i = 0; i < 100; i++) sp_mix_target_xy(&m, 0.3127f, 0.329f, 0.5f, 65535, &r);
    report("sp_mix_target_xy_4ch", since(t), 100);
    t = start();
    for (int i = 0; i < 100; i++) sp_mix_target_cct(&m, 2700.0f, 0.0f, 0.5f, 65535, &r);
    report("sp_mix_target_cct_4ch", since(t), 100);
    STACK("sp_mix_target_cct_4ch", sp_mix_target_cct(&m, 2700.0f, 0.0f, 0.5f, 65535, &r));
    m.fade_ms = 1000;
    sp_mix_target_cct(&m, 6500.0f, 0.0f, 0.9f, 65535, &r);
    t = start();
    for (int i = 0; i < 100; i++) sp_mix_step(&m, 65535, &s);
    report("sp_mix_step_4ch", since(t), 100);
    STACK("sp_mix_step_4ch", sp_mix_step(&m, 65535, &s));
    /* six channels: + amber and cyan, the solver's worst case (240 + 160 vertices) */
    static const float more[2][3] = {{0.40f, 0.45f, 0.05f}, {0.10f, 0.30f, 0.60f}};
    for (int i = 0; i < 2; i++) {
        __builtin_memcpy(m.channels[4 + i].xyz, more[i], sizeof more[i]);
        m.channels[4 + i].cost = 1.0f;
        m.channels[4 + i].gamma = 1.0f;
    }
    m.count = 6;
    m.fade_ms = 1000;
    sp_mix_target_cct(&m, 2700.0f, 0.0f, 0.3f, 65535, &r);
    t = start();
    for (int i = 0; i < 100; i++) sp_mix_step(&m, 65535, &s);
    report("sp_mix_step_6ch", since(t), 100);
    STACK("sp_mix_step_6ch", sp_mix_step(&m, 65535, &s));
    sink = (float)s.duty[0];
#endif
#if !defined(GROUP) || GROUP == 4
    SpDisplay d = {
        .primaries = {{0.64f, 0.33f}, {0.30f, 0.60f}, {0.15f, 0.06f}},
        .luminance = {21.26f, 71.52f, 7.22f},
        .gamma = {1.0f, 1.0f, 1.0f},
    };
    SpDrive dr;
    SpXyz target = {20.0f, 21.0f, 23.0f};
    t = start();
    for (int i = 0; i < 100; i++) sp_display_drive(&d, &target, SP_GAMUT_MAP_CLIP, 1023, &dr);
    report("sp_display_drive_linear", since(t), 100);
    d.gamma[0] = d.gamma[1] = d.gamma[2] = 0.0f;
    t = start();
    for (int i = 0; i < 100; i++) sp_display_drive(&d, &target, SP_GAMUT_MAP_CLIP, 1023, &dr);
    report("sp_display_drive_srgb", since(t), 100);
    STACK("sp_display_drive_srgb", sp_display_drive(&d, &target, SP_GAMUT_MAP_CLIP, 1023, &dr));
    sink = dr.emitted.y;
#endif
#if !defined(GROUP) || GROUP == 5
    static SpSpectrum sp[3], sq;
    SpXyz v;
    t = start();
    for (int i = 0; i < 3; i++) sp_spectrum_fit(SAMPLE_NM, SAMPLE_VALUE[i], SAMPLES, &sp[i]);
    report("sp_spectrum_fit_36", since(t), 3);
    STACK("sp_spectrum_fit_36", sp_spectrum_fit(SAMPLE_NM, SAMPLE_VALUE[0], SAMPLES, &sp[0]));
    t = start();
    for (int i = 0; i < 100; i++) sp_spectrum_mul(&sp[i % 3], &sp[2], &sq);
    report("sp_spectrum_mul", since(t), 100);
    STACK("sp_spectrum_mul", sp_spectrum_mul(&sp[0], &sp[2], &sq));
    t = start();
    for (int i = 0; i < 100; i++) sp_spectrum_xyz(&sp[i % 3], SP_OBSERVER_CIE1931, SP_ILLUMINANT_D65, &v);
    report("sp_spectrum_xyz", since(t), 100);
    STACK("sp_spectrum_xyz", sp_spectrum_xyz(&sp[0], SP_OBSERVER_CIE1931, SP_ILLUMINANT_D65, &v));
    float e;
    t = start();
    for (int i = 0; i < 100; i++) sp_spectrum_eval(&sp[i % 3], 400.0f + (float)i, &e);
    report("sp_spectrum_eval", since(t), 100);
    STACK("sp_spectrum_eval", sp_spectrum_eval(&sp[0], 555.0f, &e));
    sink = v.y + e + sq.coef[0][0];
#endif
#if !defined(GROUP) || GROUP == 6
    SpDisplay pd = {
        .primaries = {{0.64f, 0.33f}, {0.30f, 0.60f}, {0.15f, 0.06f}},
        .luminance = {21.26f, 71.52f, 7.22f},
        .gamma = {0.0f, 0.0f, 0.0f},
    };
    SpXyz fx;
    SpEncoded enc;
    const float rgb[3] = {0.25f, 0.5f, 0.75f};
    SpXyz want = {20.0f, 21.0f, 23.0f};
    t = start();
    for (int i = 0; i < 100; i++) sp_display_forward(&pd, rgb, &fx);
    report("sp_display_forward_srgb", since(t), 100);
    STACK("sp_display_forward_srgb", sp_display_forward(&pd, rgb, &fx));
    t = start();
    for (int i = 0; i < 100; i++) sp_display_inverse(&pd, &want, SP_GAMUT_MAP_CLIP, &enc);
    report("sp_display_inverse_srgb", since(t), 100);
    STACK("sp_display_inverse_srgb", sp_display_inverse(&pd, &want, SP_GAMUT_MAP_CLIP, &enc));
    sink = fx.y + enc.device[0];
#endif
#if !defined(GROUP) || GROUP == 7
    static SpDisplay ld;
    t = start();
    for (int i = 0; i < 10; i++) sp_calibration_load(CALIBRATION_BLOB, sizeof CALIBRATION_BLOB, &ld);
    report("sp_calibration_load", since(t), 10);
    STACK("sp_calibration_load", sp_calibration_load(CALIBRATION_BLOB, sizeof CALIBRATION_BLOB, &ld));
    sink = ld.luminance[0];
#endif
    return 0;
}
