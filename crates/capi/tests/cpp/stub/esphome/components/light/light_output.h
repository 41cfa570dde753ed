// The part of ESPHome's light interface (esphome/components/light/) that
// examples/esphome/components/specpoly_light uses, declared as ESPHome declares it, so that the
// test can compile the component without ESPHome (not installable here). Freestanding: the
// real LightTraits takes a std::set of modes; here an initializer list of one.
#pragma once
#include <stdint.h>

namespace esphome {
namespace light {

enum class ColorMode : uint8_t { UNKNOWN = 0, ON_OFF = 1, BRIGHTNESS = 2, COLOR_TEMPERATURE = 11 };

struct ColorModes {
    ColorMode mode;
};

class LightTraits {
  public:
    void set_supported_color_modes(ColorModes m) { modes_ = m; }
    void set_min_mireds(float m) { min_ = m; }
    void set_max_mireds(float m) { max_ = m; }

  private:
    ColorModes modes_{ColorMode::UNKNOWN};
    float min_ = 0.0f, max_ = 0.0f;
};

class LightColorValues {
  public:
    bool is_on() const { return state_ != 0.0f; }
    float get_brightness() const { return brightness_; }
    float get_color_temperature() const { return color_temperature_; }

  private:
    float state_ = 1.0f, brightness_ = 1.0f, color_temperature_ = 370.0f;
};

class LightState {
  public:
    LightColorValues current_values;
};

class LightOutput {
  public:
    virtual ~LightOutput() = default;
    virtual LightTraits get_traits() = 0;
    virtual void write_state(LightState *state) = 0;
};

}  // namespace light
}  // namespace esphome
