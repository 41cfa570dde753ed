/* Calls every function of specpoly.h on fixed inputs and prints one line per call: a name, the
 * status and the results, floats as their IEEE bit patterns in hex (f32: 8 digits, f64: 16), so
 * that the test (tests/c_program.rs) can compare them with the Rust API bit for bit. The same
 * source runs on the host (stdout) and, built freestanding, on a Cortex-M4F and on an RV32IMC
 * under QEMU (semihosting; start-up in arm/ and riscv/). */
#include "specpoly.h"
#include <stddef.h>
#include <stdint.h>

#include "calibration_blob.h" /* CALIBRATION_BLOB[]: written by the test (tests/c_program.rs) */
#include "spectra_samples.h"  /* SAMPLE_NM, SAMPLE_VALUE: ColorChecker reflectances */

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

static void spectrum(const char *name, SpStatus st, const SpSpectrum *s) {
    begin(name, st);
    if (st == SP_STATUS_OK)
        for (int k = 0; k < SP_SPECTRUM_COEFFS; k++)
            for (int j = 0; j < SP_SPECTRUM_SPANS; j++) f32(s->coef[k][j]);
    end();
}

static void xyz(const char *name, SpStatus st, const SpXyz *v) {
    begin(name, st);
    if (st == SP_STATUS_OK) { f32(v->x); f32(v->y); f32(v->z); }
    end();
}

static const char *const PATCH[3] = {"dark_skin", "blue_sky", "red"};

static void spectra(void) {
    const float nan = __builtin_nanf("");
    SpSpectrum r[3], r2[3];
    char name[64];
    for (int i = 0; i < 3; i++) {
        spectrum("spectrum_fit", sp_spectrum_fit(SAMPLE_NM, SAMPLE_VALUE[i], SAMPLES, &r[i]), &r[i]);
        spectrum("spectrum_mul", sp_spectrum_mul(&r[i], &r[i], &r2[i]), &r2[i]);
    }
    /* XYZ of each reflectance and its square under A, D65, FL11 for every built-in observer */
    static const int32_t LIGHT[3] = {SP_ILLUMINANT_A, SP_ILLUMINANT_D65, SP_ILLUMINANT_FL11};
    static const char *const LIGHT_NAME[3] = {"A", "D65", "FL11"};
    static const int32_t OBSERVER[4] = {SP_OBSERVER_CIE1931, SP_OBSERVER_CIE1964,
                                        SP_OBSERVER_CIE2015_2, SP_OBSERVER_CIE2015_10};
    static const char *const OBSERVER_NAME[4] = {":1931", ":1964", ":2015-2", ":2015-10"};
    for (int l = 0; l < 3; l++)
        for (int o = 0; o < 4; o++)
            for (int i = 0; i < 3; i++)
                for (int sq = 0; sq < 2; sq++) {
                    SpXyz v;
                    SpStatus st = sp_spectrum_xyz(sq ? &r2[i] : &r[i], OBSERVER[o], LIGHT[l], &v);
                    len = 0;
                    put("xyz:"); put(PATCH[i]); put(sq ? ":r2:" : ":r:"); put(LIGHT_NAME[l]);
                    put(OBSERVER_NAME[o]);
                    __builtin_memcpy(name, line, len + 1);
                    xyz(name, st, &v);
                }
    static const float AT[5] = {380.0f, 430.0f, 555.5f, 600.0f, 780.0f};
    for (int i = 0; i < 5; i++) {
        float v;
        SpStatus st = sp_spectrum_eval(&r[2], AT[i], &v);
        begin("spectrum_eval", st);
        if (st == SP_STATUS_OK) f32(v);
        end();
    }
    SpXyz w;
    xyz("light_white_d65_1931", sp_light_white(SP_OBSERVER_CIE1931, SP_ILLUMINANT_D65, &w), &w);
    xyz("light_white_fl11_1964", sp_light_white(SP_OBSERVER_CIE1964, SP_ILLUMINANT_FL11, &w), &w);
    xyz("light_white_d65_2015_10", sp_light_white(SP_OBSERVER_CIE2015_10, SP_ILLUMINANT_D65, &w), &w);

    SpSpectrum s;
    const float nm3[3] = {400.0f, 500.0f, 500.0f}, v3[3] = {0.1f, nan, 0.2f};
    spectrum("spectrum_fit_0", sp_spectrum_fit(SAMPLE_NM, SAMPLE_VALUE[0], 0, &s), &s);
    spectrum("spectrum_fit_null", sp_spectrum_fit(NULL, SAMPLE_VALUE[0], SAMPLES, &s), &s);
    spectrum("spectrum_fit_nan", sp_spectrum_fit(SAMPLE_NM, v3, 3, &s), &s);
    spectrum("spectrum_fit_not_increasing", sp_spectrum_fit(nm3, SAMPLE_VALUE[0], 3, &s), &s);
    spectrum("spectrum_mul_null", sp_spectrum_mul(&r[0], NULL, &s), &s);
    float v;
    begin("spectrum_eval_379", sp_spectrum_eval(&r[0], 379.0f, &v)); end();
    xyz("spectrum_xyz_observer_4", sp_spectrum_xyz(&r[0], 4, SP_ILLUMINANT_D65, &w), &w);
    xyz("spectrum_xyz_illuminant_7", sp_spectrum_xyz(&r[0], 0, 7, &w), &w);
    s = r[0];
    s.coef[1][3] = nan;
    xyz("spectrum_xyz_nan", sp_spectrum_xyz(&s, 0, SP_ILLUMINANT_D65, &w), &w);
}

static void forward(const char *name, const SpDisplay *d, float r, float g, float b) {
    const float rgb[3] = {r, g, b};
    SpXyz v;
    xyz(name, sp_display_forward(d, rgb, &v), &v);
}

static void inverse(const char *name, const SpDisplay *d, SpXyz t, int32_t map) {
    SpEncoded e;
    SpStatus st = sp_display_inverse(d, &t, map, &e);
    begin(name, st);
    if (st == SP_STATUS_OK) {
        for (int i = 0; i < 3; i++) f32(e.device[i]);
        for (int i = 0; i < 3; i++) f32(e.linear[i]);
        dec(e.out_of_gamut);
    }
    end();
}

static void calibration(const char *name, const uint8_t *blob, size_t n, SpDisplay *d) {
    SpStatus st = sp_calibration_load(blob, n, d);
    begin(name, st);
    if (st == SP_STATUS_OK) {
        for (int i = 0; i < 3; i++) { f32(d->primaries[i][0]); f32(d->primaries[i][1]); }
        for (int i = 0; i < 3; i++) f32(d->luminance[i]);
        for (int i = 0; i < 3; i++) f32(d->black[i]);
        for (int i = 0; i < 3; i++) f32(d->gamma[i]);
        for (int i = 0; i < 3; i++) {
            dec((int32_t)d->table_len[i]);
            for (uint32_t k = 0; k < d->table_len[i] && k < SP_DISPLAY_TABLE_MAX; k++) f32(d->table[i][k]);
        }
    }
    end();
}

static void display_model(void) {
    SpDisplay d;
    calibration("calibration_load", CALIBRATION_BLOB, sizeof CALIBRATION_BLOB, &d);
    forward("forward_white", &d, 1.0f, 1.0f, 1.0f);
    forward("forward_black", &d, 0.0f, 0.0f, 0.0f);
    forward("forward_mid", &d, 0.25f, 0.5f, 0.75f);
    forward("forward_table_knee", &d, 0.1f, 0.9f, 0.375f);
    inverse("inverse_grey", &d, (SpXyz){20.0f, 21.0f, 23.0f}, SP_GAMUT_MAP_CLIP);
    inverse("inverse_cyan_clip", &d, (SpXyz){20.0f, 40.0f, 70.0f}, SP_GAMUT_MAP_CLIP);
    inverse("inverse_cyan_desaturate", &d, (SpXyz){20.0f, 40.0f, 70.0f}, SP_GAMUT_MAP_DESATURATE);
    drive("drive_loaded", &d, (SpXyz){30.0f, 35.0f, 20.0f}, SP_GAMUT_MAP_CLIP);

    forward("forward_above_1", &d, 1.5f, 0.0f, 0.0f);
    forward("forward_nan", &d, __builtin_nanf(""), 0.0f, 0.0f);
    begin("forward_null", sp_display_forward(&d, NULL, &(SpXyz){0})); end();
    inverse("inverse_bad_map", &d, (SpXyz){20.0f, 21.0f, 23.0f}, 5);
    SpDisplay bad = d;
    bad.table_len[2] = SP_DISPLAY_TABLE_MAX + 1;
    forward("forward_table_65", &bad, 0.5f, 0.5f, 0.5f);
    bad = d;
    bad.table_len[2] = 1;
    forward("forward_table_1", &bad, 0.5f, 0.5f, 0.5f);

    /* the blob's checks: cut, corrupted, another version, none */
    static uint8_t copy[sizeof CALIBRATION_BLOB + 8];
    __builtin_memcpy(copy, CALIBRATION_BLOB, sizeof CALIBRATION_BLOB);
    calibration("calibration_longer_region", copy, sizeof copy, &bad);
    calibration("calibration_cut", copy, sizeof CALIBRATION_BLOB - 1, &bad);
    calibration("calibration_header_only", copy, 12, &bad);
    calibration("calibration_empty", copy, 0, &bad);
    copy[40] ^= 0x10;
    calibration("calibration_corrupted", copy, sizeof CALIBRATION_BLOB, &bad);
    copy[40] ^= 0x10;
    copy[4] = 2;
    calibration("calibration_version_2", copy, sizeof CALIBRATION_BLOB, &bad);
    calibration("calibration_null", NULL, sizeof CALIBRATION_BLOB, &bad);
    calibration("calibration_null_out", CALIBRATION_BLOB, sizeof CALIBRATION_BLOB, NULL);
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
    spectra();
    display_model();
    out("end\n");
    return 0;
}

#if __STDC_HOSTED__
int main(void) { return run(); }
#endif
