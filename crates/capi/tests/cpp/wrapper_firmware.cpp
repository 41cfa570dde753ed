// The C++ wrapper as firmware code, freestanding (no C++ standard library: Debian's
// cross compilers have none): compiled for a Cortex-M4F and an RV32IMC by tests/cpp.rs.
#include "specpoly.hpp"

static specpoly::Mixer lamp;
static specpoly::Panel panel;

extern "C" void pwm_write(const uint16_t *duty, uint32_t n);

extern "C" int lamp_init(const uint8_t *blob, size_t len) {
    static const float xyz[4][3] = {
        {0.65f, 0.30f, 0.0f}, {0.25f, 0.70f, 0.10f}, {0.18f, 0.08f, 0.95f}, {0.95f, 1.0f, 0.85f}};
    for (unsigned i = 0; i < 4; i++) lamp.set_channel(i, xyz[i][0], xyz[i][1], xyz[i][2]);
    lamp.set_count(4);
    lamp.set_fade_ms(2000);
    return panel.load(blob, len);
}

extern "C" int lamp_set(float cct, float duv, float brightness) {
    SpMixResult r;
    return lamp.target_cct(cct, duv, brightness, 65535, r);
}

extern "C" void lamp_tick_10ms(void) {
    SpMixStep s;
    if (specpoly::ok(lamp.step(65535, s))) pwm_write(s.duty, lamp.count());
}

extern "C" int panel_code(float x, float y, float z, uint16_t *level) {
    SpDrive d;
    specpoly::Status s = panel.drive(SpXyz{x, y, z}, SP_GAMUT_MAP_DESATURATE, 1023, d);
    if (specpoly::ok(s))
        for (int i = 0; i < 3; i++) level[i] = d.level[i];
    return s;
}
