/* specpoly-c for C++: a header-only wrapper over specpoly.h (docs/c.md). No exceptions, no
 * allocation, no RTTI: every call returns the library's SpStatus; the classes own their C
 * structs (caller-owned state, as the C API has it) and check nothing twice. C++11 or later;
 * compiled by the test `cpp::the_wrapper_and_the_examples_compile_for_the_host_a_cortex_m4f_and_an_rv32imc`. */
#ifndef SPECPOLY_HPP
#define SPECPOLY_HPP

#include "specpoly.h"

namespace specpoly {

using Status = SpStatus;

/* Whether a status is success (SP_STATUS_OK; SP_STATUS_FADE_DONE is not an error either). */
inline bool ok(Status s) { return s == SP_STATUS_OK; }

/* CCT (K) and Duv → CIE 1931 xy. */
inline Status cct_to_xy(float cct, float duv, SpXy &out) { return sp_cct_to_xy(cct, duv, &out); }

/* CIE 1931 xy → CCT and Duv (costly: for reports, not loops). */
inline Status xy_to_cct(double x, double y, SpCct &out) { return sp_xy_to_cct(x, y, &out); }

/* 3 to SP_MAX_CHANNELS LED channels mixed to an xy or CCT/Duv target, with the fade. */
class Mixer {
  public:
    Mixer() { sp_mixer_init(&m_); }

    /* Channel i's XYZ at full drive, its weight in the drive minimised (1: least total drive)
     * and its curve (1: linear PWM, 0: sRGB, else the exponent). Returns SP_STATUS_CHANNELS for
     * an index past SP_MAX_CHANNELS. */
    Status set_channel(unsigned i, float x, float y, float z, float cost = 1.0f,
                       float gamma = 1.0f) {
        if (i >= SP_MAX_CHANNELS) return SP_STATUS_CHANNELS;
        SpChannel &c = m_.channels[i];
        c.xyz[0] = x;
        c.xyz[1] = y;
        c.xyz[2] = z;
        c.cost = cost;
        c.gamma = gamma;
        return SP_STATUS_OK;
    }
    void set_count(uint32_t n) { m_.count = n; }
    void set_fade_ms(uint32_t ms) { m_.fade_ms = ms; }
    uint32_t count() const { return m_.count; }

    Status target_xy(float x, float y, float lum, uint16_t max, SpMixResult &out) {
        return sp_mix_target_xy(&m_, x, y, lum, max, &out);
    }
    Status target_cct(float cct, float duv, float lum, uint16_t max, SpMixResult &out) {
        return sp_mix_target_cct(&m_, cct, duv, lum, max, &out);
    }
    /* One fade step (every 10 ms): SP_STATUS_OK with the duties, SP_STATUS_FADE_DONE when
     * none is pending. */
    Status step(uint16_t max, SpMixStep &out) { return sp_mix_step(&m_, max, &out); }

    const SpMixer &raw() const { return m_; }
    SpMixer &raw() { return m_; }

  private:
    SpMixer m_;
};

/* A display (or RGB LED) model: set its fields, or load a calibration blob. */
class Panel {
  public:
    Panel() : d_() {}

    /* From `specpoly calibrate export --format c-blob`: SP_STATUS_BLOB_VERSION,
     * SP_STATUS_BLOB_CHECKSUM, SP_STATUS_BLOB_TRUNCATED for a blob this build cannot trust
     * (the panel is then unchanged). */
    Status load(const uint8_t *blob, size_t len) { return sp_calibration_load(blob, len, &d_); }

    Status drive(const SpXyz &target, SpGamutMap map, uint16_t max, SpDrive &out) const {
        return sp_display_drive(&d_, &target, static_cast<int32_t>(map), max, &out);
    }
    Status forward(const float rgb[3], SpXyz &out) const {
        return sp_display_forward(&d_, rgb, &out);
    }
    Status inverse(const SpXyz &xyz, SpGamutMap map, SpEncoded &out) const {
        return sp_display_inverse(&d_, &xyz, static_cast<int32_t>(map), &out);
    }

    const SpDisplay &raw() const { return d_; }
    SpDisplay &raw() { return d_; }

  private:
    SpDisplay d_;
};

/* A spectrum: 8 uniform cubic spans over 380–780 nm. */
class Spectrum {
  public:
    Spectrum() : s_() {}

    /* Least-squares fit to n samples (nm strictly increasing). */
    static Status fit(const float *nm, const float *value, size_t n, Spectrum &out) {
        return sp_spectrum_fit(nm, value, n, &out.s_);
    }
    Status eval(float nm, float &out) const { return sp_spectrum_eval(&s_, nm, &out); }
    /* this · o, reduced to cubics. */
    Status mul(const Spectrum &o, Spectrum &out) const {
        return sp_spectrum_mul(&s_, &o.s_, &out.s_);
    }
    /* CIE XYZ (white Y = 100) under a built-in light for an observer. */
    Status xyz(SpObserver observer, SpIlluminant light, SpXyz &out) const {
        return sp_spectrum_xyz(&s_, static_cast<int32_t>(observer), static_cast<int32_t>(light),
                               &out);
    }

    const SpSpectrum &raw() const { return s_; }
    SpSpectrum &raw() { return s_; }

  private:
    SpSpectrum s_;
};

} // namespace specpoly

#endif
