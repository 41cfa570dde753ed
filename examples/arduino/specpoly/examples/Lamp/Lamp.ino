// A four-channel lamp (red, green, blue, white LEDs on PWM pins) fading between colour
// temperatures on the Planckian locus: specpoly::Mixer solves each 10 ms fade step.
#include <Arduino.h>
#include <specpoly.hpp>

static const uint8_t PIN[4] = {5, 6, 9, 10};
static specpoly::Mixer lamp;
static unsigned long last = 0;

void setup() {
    // each LED's CIE XYZ at full duty: measured with a colorimeter, or from `specpoly mix`
    static const float xyz[4][3] = {
        {0.65f, 0.30f, 0.0f}, {0.25f, 0.70f, 0.10f}, {0.18f, 0.08f, 0.95f}, {0.95f, 1.0f, 0.85f}};
    for (unsigned i = 0; i < 4; i++) lamp.set_channel(i, xyz[i][0], xyz[i][1], xyz[i][2]);
    lamp.set_count(4);
    lamp.set_fade_ms(3000);
    SpMixResult r;
    lamp.target_cct(2700.0f, 0.0f, 0.8f, 255, r);
}

void loop() {
    unsigned long now = millis();
    if (now - last < 10) return;
    last = now;
    SpMixStep s;
    if (lamp.step(255, s) == SP_STATUS_OK) {
        for (unsigned i = 0; i < 4; i++) analogWrite(PIN[i], s.duty[i]);
    } else {
        // the fade is done: go to the other end of the range
        static bool warm = false;
        SpMixResult r;
        lamp.target_cct(warm ? 2700.0f : 6500.0f, 0.0f, 0.8f, 255, r);
        warm = !warm;
    }
}
