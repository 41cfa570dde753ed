// Instantiates the ESPHome example component (freestanding, against the stub interface).
#include "specpoly_light.h"

namespace {
class Pwm : public esphome::output::FloatOutput {
  public:
    float level = 0.0f;

  protected:
    void write_state(float s) override { level = s; }
};
}  // namespace

extern "C" float esphome_component_demo(void) {
    static Pwm pwm[4];
    static esphome::specpoly_light::SpecpolyLight lamp;
    static const float xyz[4][3] = {
        {0.65f, 0.30f, 0.0f}, {0.25f, 0.70f, 0.10f}, {0.18f, 0.08f, 0.95f}, {0.95f, 1.0f, 0.85f}};
    for (int i = 0; i < 4; i++) lamp.add_channel(&pwm[i], xyz[i][0], xyz[i][1], xyz[i][2]);
    esphome::light::LightState state;
    lamp.get_traits();
    lamp.write_state(&state);
    return pwm[3].level;
}
