//! Numbers in messages as a reader would write them: 0.25 and 19,000, not 2.5e-1 and 1.9e4;
//! scientific notation only for the very small or very large.

/// `x` as a reader would write it: plainly from 1e-4 to 1e15 (0.25, 3.141592653589793, 100000),
/// in scientific notation beyond (1e-300, 2.5e20), and 0, NaN, inf, -inf as such. The digits are the
/// shortest that give `x` back, so no two different values print alike.
///
/// ```
/// use rtl_exercises::check::num;
/// assert_eq!(num(0.25), "0.25");
/// assert_eq!(num(0.0), "0");
/// assert_eq!(num(1e-300), "1e-300");
/// ```
pub fn num(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// `x` rounded to `digits` significant digits, plainly from 1e-4 to 1e15 (0.00519, 2.67),
/// in scientific notation beyond (5.19e-12); trailing zeros are dropped (0.9, not 0.900).
///
/// ```
/// use rtl_exercises::check::sig;
/// assert_eq!(sig(0.005191234, 3), "0.00519");
/// assert_eq!(sig(2.0 / 3.0, 4), "0.6667");
/// assert_eq!(sig(1234.5, 2), "1200");
/// ```
pub fn sig(x: f64, digits: usize) -> String {
    let digits = digits.max(1);
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let exponent = x.abs().log10().floor() as i32;
    if (-4..15).contains(&exponent) {
        let decimals = (digits as i32 - 1 - exponent).max(0) as usize;
        let scale = 10f64.powi(exponent + 1 - digits as i32);
        let rounded = if decimals == 0 {
            (x / scale).round() * scale
        } else {
            x
        };
        trim_zeros(&format!("{rounded:.decimals$}"))
    } else {
        let text = format!("{x:.prec$e}", prec = digits - 1);
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        format!("{}e{exponent}", trim_zeros(mantissa))
    }
}

/// "0.900" -> "0.9", "1.00" -> "1", "120" -> "120".
fn trim_zeros(text: &str) -> String {
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text.to_string()
    }
}

/// A p-value: 2 significant digits, or "< 1e-300" where it underflows to 0.
pub(super) fn p_value(p: f64) -> String {
    if p == 0.0 {
        "< 1e-300".to_string()
    } else {
        format!("= {}", sig(p, 2))
    }
}

/// A count with thousands separators: 19,000.
pub fn count(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// An expected count: whole (19,000) from 10 on, to one decimal below (2.5).
pub(super) fn expected_count(e: f64) -> String {
    if e >= 10.0 {
        count(e.round() as u64)
    } else {
        format!("{e:.1}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::*;

    #[test]
    fn numbers_print_plainly_unless_very_small_or_large() {
        assert_eq!(num(0.0), "0");
        assert_eq!(num(0.25), "0.25");
        assert_eq!(num(0.0625), "0.0625");
        assert_eq!(num(-3.0), "-3");
        assert_eq!(num(1e-9), "1e-9");
        assert_eq!(num(2.5e20), "2.5e20");
        assert_eq!(num(f64::NAN), "NaN");
        assert_eq!(sig(0.00519, 3), "0.00519");
        assert_eq!(sig(1.23456789, 6), "1.23457");
        assert_eq!(sig(5.19e-12, 3), "5.19e-12");
        assert_eq!(sig(0.9, 3), "0.9");
        assert_eq!(sig(5e-12, 3), "5e-12");
        assert_eq!(count(19_000), "19,000");
        assert_eq!(count(999), "999");
        assert_eq!(count(1_234_567), "1,234,567");
        let err = close("f(1)", 0.25, 0.5, 1e-15).unwrap_err();
        assert_eq!(err, "f(1): got 0.25, expected 0.5 (to a relative 1e-15)");
        let err = close("f(0)", 1e-300, 0.0, 0.0).unwrap_err();
        assert_eq!(err, "f(0): got 1e-300, expected exactly 0");
    }
}
