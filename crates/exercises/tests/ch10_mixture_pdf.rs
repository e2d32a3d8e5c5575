//! Runs the checks of `exercises/ch10_mixture_pdf.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch10_mixture_pdf.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch10_mixture_pdf.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch10_mixture_pdf.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch10_mixture_pdf::*;

rtl_exercises::exercise_main!("ch10_mixture_pdf", e => {
    "value at 1000 directions, for weights 0, 0.3 and 1" => check_value(|a, b, weight_a| e::MixturePdf { a, b, weight_a }),
    "a part of weight 0 is neither evaluated nor sampled" => check_weight_zero(|a, b, weight_a| e::MixturePdf { a, b, weight_a }, |a, b, weight_a| e::MixturePdf { a, b, weight_a }),
    "generate samples what value says (chi-square)" => check_generate(|a, b, weight_a| e::MixturePdf { a, b, weight_a }),
});
