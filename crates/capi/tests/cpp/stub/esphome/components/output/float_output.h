// ESPHome's output::FloatOutput as the example uses it (see ../light/light_output.h).
#pragma once

namespace esphome {
namespace output {

class FloatOutput {
  public:
    virtual ~FloatOutput() = default;
    void set_level(float level) { write_state(level); }

  protected:
    virtual void write_state(float state) = 0;
};

}  // namespace output
}  // namespace esphome
