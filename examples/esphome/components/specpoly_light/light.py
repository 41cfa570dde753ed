"""ESPHome code generation for specpoly_light (ESPHome's external-component conventions; not run
here: ESPHome is not installable in this repository's test environment)."""

import esphome.codegen as cg
import esphome.config_validation as cv
from esphome.components import light, output
from esphome.const import CONF_OUTPUT_ID

specpoly_ns = cg.esphome_ns.namespace("specpoly_light")
SpecpolyLight = specpoly_ns.class_("SpecpolyLight", light.LightOutput)

CONF_CHANNELS = "channels"
CONF_OUTPUT = "output"
CONF_XYZ = "xyz"
CONF_WARM_KELVIN = "warm_kelvin"
CONF_COLD_KELVIN = "cold_kelvin"

CHANNEL = cv.Schema(
    {
        cv.Required(CONF_OUTPUT): cv.use_id(output.FloatOutput),
        cv.Required(CONF_XYZ): cv.All([cv.float_], cv.Length(min=3, max=3)),
    }
)

CONFIG_SCHEMA = light.BRIGHTNESS_ONLY_LIGHT_SCHEMA.extend(
    {
        cv.GenerateID(CONF_OUTPUT_ID): cv.declare_id(SpecpolyLight),
        cv.Required(CONF_CHANNELS): cv.All([CHANNEL], cv.Length(min=3, max=6)),
        cv.Optional(CONF_WARM_KELVIN, default=2700.0): cv.float_range(min=1000, max=25000),
        cv.Optional(CONF_COLD_KELVIN, default=6500.0): cv.float_range(min=1000, max=25000),
    }
)


async def to_code(config):
    var = cg.new_Pvariable(config[CONF_OUTPUT_ID])
    await light.register_light(var, config)
    for ch in config[CONF_CHANNELS]:
        out = await cg.get_variable(ch[CONF_OUTPUT])
        x, y, z = ch[CONF_XYZ]
        cg.add(var.add_channel(out, x, y, z))
    cg.add(var.set_range_kelvin(config[CONF_WARM_KELVIN], config[CONF_COLD_KELVIN]))
    # the header and the staticlib for the target (docs/c.md, "Building and linking")
    cg.add_build_flag("-lspecpoly_c")
