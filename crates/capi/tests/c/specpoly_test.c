/* Calls every function of specpoly.h on fixed inputs and prints one line per call: a name, the
 * status and the results, floats as their IEEE bit patterns in hex (f32: 8 digits, f64: 16), so
 * that the test (tests/c_program.rs) can compare them with the Rust API bit for bit. The same
 * source runs on the host (stdout) and, built freestanding, on a Cortex-M4F and on an RV32IMC
 * under QEMU (semihosting; start-up in arm/ and riscv/). */
#include "specpoly.h"
#include <stddef.h>
#include <stdint.h>

#if __STDC_HOSTED__
#include <stdio.h>
static void out(const char *s) { fputs(s, stdout); }
#elif defined(__arm__)
/* semihosting SYS_WRITE0 */
static void out(const char *s) {
    register int r0 __asm__("r0") = 0x04;
    register const char *r1 __asm__("r1") = s;
    __asm__ volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
}
#elif defined(__riscv)
/* semihosting SYS_WRITE0: the RISC-V semihosting sequence, uncompressed */
static void out(const char *s) {
    register long a0 __asm__("a0") = 0x04;
    register const char *a1 __asm__("a1") = s;
    __asm__ volatile(".option push\n.option norvc\n"
                     "slli x0, x0, 0x1f\nebreak\nsrai x0, x0, 7\n.option pop"
                     : "+r"(a0) : "r"(a1) : "memory");
}
#endif

static char line[512];
static size_t len;

static void put(const char *s) {
    while (*s && len + 1 < sizeof line) line[len++] = *s++;
    line[len] = 0;
}
static void hex(uint64_t v, int digits) {
    char b[20];
    b[0] = ' ';
    for (int i = 0; i < digits; i++) b[1 + i] = "0123456789abcdef"[(v >> (4 * (digits - 1 - i))) & 15];
    b[1 + digits] = 0;
    put(b);
}
static void f32(float f) { uint32_t u; __builtin_memcpy(&u, &f, 4); hex(u, 8); }
static void f64(double f) { uint64_t u; __builtin_memcpy(&u, &f, 8); hex(u, 16); }
static void dec(int32_t v) {
    char b[16];
    int i = 15;
    uint32_t u = v < 0 ? (uint32_t)(-(int64_t)v) : (uint32_t)v;
    b[i--] = 0;
    do { b[i--] = (char)('0' + u % 10); u /= 10; } while (u);
    if (v < 0) b[i--] = '-';
    b[i] = ' ';
    put(b + i);
}
static void begin(const char *name, SpStatus st) { len = 0; put(name); dec(st); }
static void end(void) { put("\n"); out(line); }

static void cct_to_xy(const char *name, float cct, float duv) {
    SpXy xy;
    SpStatus st = sp_cct_to_xy(cct, duv, &xy);
    begin(name, st);
    if (st == SP_STATUS_OK) { f32(xy.x); f32(xy.y); }
    end();
}

static void xy_to_cct(const char *name, double x, double y) {
    SpCct c;
    SpStatus st = sp_xy_to_cct(x, y, &c);
    begin(name, st);
    if (st == SP_STATUS_OK) { f64(c.cct); f64(c.duv); }
    end();
}

static void mix_result(const char *name, SpStatus st, const SpMixResult *r) {
    begin(name, st);
    if (st == SP_STATUS_OK) {
        f32(r->point.u); f32(r->point.v); f32(r->point.lum); f32(r->xy.x); f32(r->xy.y);
        for (int i = 0; i < SP_MAX_CHANNELS; i++) f32(r->light[i]);
        for (int i = 0; i < SP_MAX_CHANNELS; i++) dec(r->duty[i]);
        dec((int32_t)r->steps);
    }
    end();
}

static void drive(const char *name, const SpDisplay *d, SpXyz t, int32_t map) {
    SpDrive r;
    SpStatus st = sp_display_drive(d, &t, map, 1023, &r);
    begin(name, st);
    if (st == SP_STATUS_OK) {
        for (int i = 0; i < 3; i++) f32(r.linear[i]);
        for (int i = 0; i < 3; i++) dec(r.level[i]);
        f32(r.emitted.x); f32(r.emitted.y); f32(r.emitted.z);
        dec(r.out_of_gamut);
    }
    end();
}

/* red, green, blue and a white LED: XYZ at full drive */
static const float RGBW[4][3] = {
    {0.65f, 0.30f, 0.0f}, {0.25f, 0.70f, 0.10f}, {0.18f, 0.08f, 0.95f}, {0.95f, 1.0f, 0.85f},
};

static void rgbw(SpMixer *m) {
    sp_mixer_init(m);
    m->count = 4;
    for (int i = 0; i < 4; i++) {
        __builtin_memcpy(m->channels[i].xyz, RGBW[i], sizeof RGBW[i]);
        m->channels[i].cost = 1.0f;
        m->channels[i].gamma = i == 3 ? 2.2f : 1.0f;
    }
}

int run(void) {
    const float nan = __builtin_nanf("");
    const float inf = __builtin_inff();

    cct_to_xy("cct_to_xy_2700", 2700.0f, 0.0f);
    cct_to_xy("cct_to_xy_6500_p01", 6500.0f, 0.01f);
    cct_to_xy("cct_to_xy_1000_m05", 1000.0f, -0.05f);
    cct_to_xy("cct_to_xy_25000_p05", 25000.0f, 0.05f);
    cct_to_xy("cct_to_xy_nan", nan, 0.0f);
    cct_to_xy("cct_to_xy_inf_duv", 4000.0f, inf);
    cct_to_xy("cct_to_xy_500", 500.0f, 0.0f);
    cct_to_xy("cct_to_xy_duv_06", 4000.0f, 0.06f);
    cct_to_xy("cct_to_xy_1000_p05", 1000.0f, 0.05f);
    begin("cct_to_xy_null", sp_cct_to_xy(4000.0f, 0.0f, NULL)); end();

    xy_to_cct("xy_to_cct_d65", 0.3127, 0.3290);
    xy_to_cct("xy_to_cct_a", 0.44757, 0.40745);
    xy_to_cct("xy_to_cct_far", 0.7, 0.29);
    xy_to_cct("xy_to_cct_nan", 0.3, __builtin_nan(""));
    xy_to_cct("xy_to_cct_outside", 0.6, 0.6);
    begin("xy_to_cct_null", sp_xy_to_cct(0.3, 0.3, NULL)); end();

    SpMixer m;
    SpMixResult r;
    rgbw(&m);
    mix_result("mix_xy_d65", sp_mix_target_xy(&m, 0.3127f, 0.329f, 0.5f, 65535, &r), &r);
    mix_result("mix_cct_2700", sp_mix_target_cct(&m, 2700.0f, 0.0f, 0.2f, 65535, &r), &r);
    m.fade_ms = 250;
    mix_result("mix_cct_6500_fade", sp_mix_target_cct(&m, 6500.0f, 0.003f, 0.9f, 65535, &r), &r);
    for (;;) {
        SpMixStep s;
        SpStatus st = sp_mix_step(&m, 65535, &s);
        begin("mix_step", st);
        if (st == SP_STATUS_OK) {
            dec((int32_t)s.step); dec((int32_t)s.steps);
            f32(s.point.u); f32(s.point.v); f32(s.point.lum);
            for (int i = 0; i < SP_MAX_CHANNELS; i++) dec(s.duty[i]);
        }
        end();
        if (st != SP_STATUS_OK) break;
    }
    mix_result("mix_out_of_gamut", sp_mix_target_xy(&m, 0.08f, 0.85f, 1.0f, 65535, &r), &r);
    mix_result("mix_nan_lum", sp_mix_target_xy(&m, 0.3f, 0.3f, nan, 65535, &r), &r);
    mix_result("mix_lum_above_1", sp_mix_target_xy(&m, 0.3f, 0.3f, 1.5f, 65535, &r), &r);
    mix_result("mix_cct_900", sp_mix_target_cct(&m, 900.0f, 0.0f, 1.0f, 65535, &r), &r);
    mix_result("mix_null_out", sp_mix_target_xy(&m, 0.3f, 0.3f, 1.0f, 65535, NULL), &r);
    mix_result("mix_null_mixer", sp_mix_target_xy(NULL, 0.3f, 0.3f, 1.0f, 65535, &r), &r);
    begin("mix_step_null", sp_mix_step(&m, 65535, NULL)); end();
    m.count = 7;
    mix_result("mix_7_channels", sp_mix_target_xy(&m, 0.3f, 0.3f, 1.0f, 65535, &r), &r);
    m.count = 2;
    mix_result("mix_2_channels", sp_mix_target_xy(&m, 0.3f, 0.3f, 1.0f, 65535, &r), &r);
    rgbw(&m);
    m.channels[1].xyz[2] = nan;
    mix_result("mix_nan_channel", sp_mix_target_xy(&m, 0.3f, 0.3f, 1.0f, 65535, &r), &r);
    rgbw(&m);
    m.channels[0].gamma = -1.0f;
    mix_result("mix_negative_gamma", sp_mix_target_xy(&m, 0.3f, 0.3f, 1.0f, 65535, &r), &r);
    begin("mixer_init_null", sp_mixer_init(NULL)); end();

    /* an sRGB-like panel, white Y = 100 (primaries' luminances 21.26, 71.52, 7.22) */
    SpDisplay d = {
        .primaries = {{0.64f, 0.33f}, {0.30f, 0.60f}, {0.15f, 0.06f}},
        .luminance = {21.26f, 71.52f, 7.22f},
        .black = {0.05f, 0.05f, 0.06f},
        .gamma = {0.0f, 2.2f, 1.0f},
    };
    drive("drive_white", &d, (SpXyz){95.047f, 100.0f, 108.883f}, SP_GAMUT_MAP_CLIP);
    drive("drive_grey", &d, (SpXyz){20.0f, 21.0f, 23.0f}, SP_GAMUT_MAP_CLIP);
    drive("drive_cyan_clip", &d, (SpXyz){20.0f, 40.0f, 70.0f}, SP_GAMUT_MAP_CLIP);
    drive("drive_cyan_desaturate", &d, (SpXyz){20.0f, 40.0f, 70.0f}, SP_GAMUT_MAP_DESATURATE);
    drive("drive_nan", &d, (SpXyz){nan, 40.0f, 70.0f}, SP_GAMUT_MAP_CLIP);
    drive("drive_bad_map", &d, (SpXyz){20.0f, 40.0f, 70.0f}, 2);
    begin("drive_null_display", sp_display_drive(NULL, &(SpXyz){1, 1, 1}, 0, 255, NULL)); end();
    begin("drive_null_target", sp_display_drive(&d, NULL, 0, 255, &(SpDrive){0})); end();
    SpDisplay bad = d;
    bad.primaries[2][1] = 0.0f;
    drive("drive_singular", &bad, (SpXyz){20.0f, 21.0f, 23.0f}, SP_GAMUT_MAP_CLIP);
    bad = d;
    bad.luminance[0] = inf;
    drive("drive_inf_display", &bad, (SpXyz){20.0f, 21.0f, 23.0f}, SP_GAMUT_MAP_CLIP);
    out("end\n");
    return 0;
}

#if __STDC_HOSTED__
int main(void) { return run(); }
#endif
