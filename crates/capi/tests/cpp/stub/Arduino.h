// The Arduino API the example sketch (examples/arduino/specpoly/examples/Lamp) calls, declared
// as Arduino declares it, so that the test can compile the sketch without an Arduino core.
#pragma once
#include <stdint.h>

extern "C" unsigned long millis(void);
void analogWrite(uint8_t pin, int value);
