// An ESPHome external component: a colour-temperature light on 3 to 6 PWM channels (RGB, RGBW,
// RGBWW, ...) mixed by specpoly-c to the exact CCT on the Planckian locus (Duv 0) and the
// brightness asked, instead of ESPHome's mired-linear two-white mix. ESPHome's own transitions
// call write_state() with the in-between values; each call solves the mix (≈ 7 000
// instructions on a Cortex-M4F, 70 000 in soft float on an ESP32-C3: docs/performance.md).
//
// Uses only this interface of ESPHome: light::LightOutput (get_traits, write_state),
// light::LightTraits (set_supported_color_modes, set_min_mireds, set_max_mireds),
// light::LightState::current_values (get_color_temperature in mireds, get_brightness,
// is_on), output::FloatOutput::set_level. ESPHome itself is not installable here: the test
// compiles this file against a stub of exactly that interface (crates/capi/tests/cpp/stub/).
#pragma once

#include "esphome/components/light/light_output.h"
#include "esphome/components/output/float_output.h"
#include "specpoly.hpp"

namespace esphome {
namespace specpoly_light {

class SpecpolyLight : public light::LightOutput {
  public:
    // Channel i: its PWM output and its CIE 1931 X, Y, Z at full duty (measured with a
    // colorimeter, or from `specpoly mix`).
    void add_channel(output::FloatOutput *out, float x, float y, float z) {
        if (count_ >= SP_MAX_CHANNELS) return;
        mixer_.set_channel(count_, x, y, z);
        out_[count_++] = out;
        mixer_.set_count(count_);
    }
    void set_range_kelvin(float warm, float cold) {
        warm_mireds_ = 1e6f / warm;
        cold_mireds_ = 1e6f / cold;
    }

    light::LightTraits get_traits() override {
        light::LightTraits t;
        t.set_supported_color_modes({light::ColorMode::COLOR_TEMPERATURE});
        t.set_min_mireds(cold_mireds_);
        t.set_max_mireds(warm_mireds_);
        return t;
    }

    void write_state(light::LightState *state) override {
        const light::LightColorValues &v = state->current_values;
        if (!v.is_on() || v.get_brightness() <= 0.0f) {
            for (uint32_t i = 0; i < count_; i++) out_[i]->set_level(0.0f);
            return;
        }
        SpMixResult r;
        float cct = 1e6f / v.get_color_temperature();
        // out of gamut or out of range: keep what is shown
        if (!specpoly::ok(mixer_.target_cct(cct, 0.0f, v.get_brightness(), 65535, r))) return;
        for (uint32_t i = 0; i < count_; i++) out_[i]->set_level(r.duty[i] / 65535.0f);
    }

  private:
    specpoly::Mixer mixer_;
    output::FloatOutput *out_[SP_MAX_CHANNELS] = {};
    uint32_t count_ = 0;
    float warm_mireds_ = 1e6f / 2700.0f;
    float cold_mireds_ = 1e6f / 6500.0f;
};

}  // namespace specpoly_light
}  // namespace esphome
