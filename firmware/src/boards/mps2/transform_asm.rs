//! The per-pixel transform of the framebuffer kernels ([`super::rgb565`], [`super::rgb888`]) as
//! assembler text, written once: decode (three byte loads, three table loads), the 3×3 in Q14
//! (`PKHBT`, 3 × `SMUL<x>B` + `SMLAD`) and each channel's inverse-curve index (three `USAT`
//! ramps, `Σ usat(acc >> (14 + a), n)`) and table load. The kernels differ only in how two
//! coefficient words come off their stack (one `LDRD`, or one `LDM` that restores `r8` too) and
//! in their curve tables' entries (RGB565: u16 levels, RGB888: u8 codes), so the macro takes
//! those; the dither, pack and store follow it in each kernel. Leaves the R, G, B entries in
//! `r10`, `r12`, `r11`.
//!
//! Registers: `r0` source (advanced by 3), `r2` decode table, `r3`/`r4`/`r5` curve tables R/G/B,
//! `r6`/`r7` `m01` R/G, `r8` `m2rg`; temporaries `r9`–`r12`, `lr`. A Rust macro (text spliced with
//! `concat!` into each `global_asm!`) rather than an assembler `.macro`: all `global_asm!`
//! blocks of the crate end up in one assembly unit, where a `.macro` defined in two of them
//! would clash and one defined in only one would depend on their order.

/// The transform's assembler text. `$coef`: one instruction that loads `m2b` into `r11` and
/// `m01b` into `r12` (`r9`, `r10` and `lr` are live; `r8` may be reloaded too); `$scale`: the
/// index operand's shift, `", lsl #1"` for u16 curve entries, `""` for u8; `$load`: `"ldrh"` or
/// `"ldrb"`.
macro_rules! transform_asm {
    ($coef:literal, $scale:literal, $load:literal) => {
        concat!(
            "    ldrb    r9, [r0, #2]
    ldrb    r10, [r0, #1]
    ldrb    r11, [r0], #3
    ldrh    r9, [r2, r9, lsl #1]        @ d2
    ldrh    r10, [r2, r10, lsl #1]      @ d1
    ldrh    r11, [r2, r11, lsl #1]      @ d0
    pkhbt   r10, r11, r10, lsl #16      @ d0 | d1 << 16
    ",
            $coef,
            "          @ r11 m2b, r12 m01b
    smulbb  r11, r11, r9
    smlad   r11, r12, r10, r11          @ acc B
    smultb  r12, r8, r9
    smlad   r12, r7, r10, r12           @ acc G
    smulbb  r9, r8, r9
    smlad   r10, r6, r10, r9            @ acc R
    usat    r9, #7, r10, asr #16        @ R: index = sum of usat(acc >> (14 + a), n)
    add     r9, r3, r9",
            $scale,
            "
    usat    lr, #9, r10, asr #18
    add     r9, r9, lr",
            $scale,
            "
    usat    r10, #9, r10, asr #20
    ",
            $load,
            "    r10, [r9, r10",
            $scale,
            "]      @ R
    usat    r9, #7, r12, asr #16        @ G
    add     r9, r4, r9",
            $scale,
            "
    usat    lr, #9, r12, asr #18
    add     r9, r9, lr",
            $scale,
            "
    usat    r12, #9, r12, asr #20
    ",
            $load,
            "    r12, [r9, r12",
            $scale,
            "]      @ G
    usat    r9, #7, r11, asr #16        @ B
    add     r9, r5, r9",
            $scale,
            "
    usat    lr, #9, r11, asr #18
    add     r9, r9, lr",
            $scale,
            "
    usat    r11, #9, r11, asr #20
    ",
            $load,
            "    r11, [r9, r11",
            $scale,
            "]      @ B
"
        )
    };
}
pub(crate) use transform_asm;
