//! Text that comes from outside (a scene file's keys and strings, a checkpoint's header) as a
//! message shows it on a terminal: what would act rather than show (an escape sequence, a
//! right-to-left override) written out as `\u{...}`, and what is too long cut short.

/// The most characters of one outside string a message shows.
pub const SHOWN_CHARS: usize = 200;

/// Whether `c` changes how a terminal shows what follows instead of showing itself: a control
/// character (other than tab and line ends, which text may hold) or a bidirectional control
/// (U+061C, U+200E, U+200F, U+202A to U+202E, U+2066 to U+2069), with which a line can be made to
/// read otherwise than it is ("Trojan Source", Boucher and Anderson 2021).
pub fn acts(c: char) -> bool {
    (c.is_control() && !matches!(c, '\t' | '\n' | '\r'))
        || matches!(
            c,
            '\u{061C}' | '\u{200E}' | '\u{200F}' | '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}'
        )
}

/// Whether `c` shows as nothing (a zero-width space or joiner, a soft hyphen, a byte-order mark, a
/// line or paragraph separator, an invisible operator): two names that differ by one read alike.
pub fn invisible(c: char) -> bool {
    matches!(
        c,
        '\u{00AD}'
            | '\u{034F}'
            | '\u{200B}'..='\u{200D}'
            | '\u{2028}'
            | '\u{2029}'
            | '\u{2060}'..='\u{2064}'
            | '\u{206A}'..='\u{206F}'
            | '\u{FEFF}'
            | '\u{FFF9}'..='\u{FFFB}'
    )
}

/// `s` for a one-line message: every character that [`acts`] or is [`invisible`], and tab and
/// line ends, as `\u{XXXX}`, and at most [`SHOWN_CHARS`] characters of it, the rest counted.
pub fn shown(s: &str) -> String {
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i == SHOWN_CHARS {
            let rest = s.chars().count() - SHOWN_CHARS;
            out.push_str(&format!("... ({rest} more characters)"));
            break;
        }
        if acts(c) || invisible(c) || matches!(c, '\t' | '\n' | '\r') {
            out.push_str(&format!("\\u{{{:04X}}}", c as u32));
        } else {
            out.push(c);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn what_would_act_on_a_terminal_is_written_out_and_long_text_cut() {
        assert_eq!(shown("cornell"), "cornell");
        assert_eq!(shown("a\u{1b}[2Jb"), "a\\u{001B}[2Jb");
        assert_eq!(shown("x\u{202E}y\u{9b}"), "x\\u{202E}y\\u{009B}");
        assert_eq!(shown("two\nlines"), "two\\u{000A}lines");
        let long = "é".repeat(SHOWN_CHARS + 5);
        assert_eq!(
            shown(&long),
            format!("{}... (5 more characters)", "é".repeat(SHOWN_CHARS))
        );
        assert!(acts('\u{2067}') && acts('\u{7f}') && !acts('\t') && !acts('é'));
        // what shows as nothing is written out too (`mar\u{200D}ble` read as `marble`)
        assert_eq!(shown("mar\u{200D}ble\u{FEFF}"), "mar\\u{200D}ble\\u{FEFF}");
    }
}
