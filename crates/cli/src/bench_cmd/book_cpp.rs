//! The book's C++ program, patched in a scratch copy to the comparison's settings.
//!
//! The book's `main.cc` compiles its image width, samples per pixel and depth in, and its
//! `random_double` is `rand()`, never seeded. The harness writes a patched copy of `main.cc` into its
//! scratch directory (its headers are still read from the checkout, by `-I`): the copy sets those
//! three constants and calls `srand(SEED)` first thing in `main`, so that two runs are independent
//! renders. The checkout itself is never modified, and none of its code is part of this project.

use thiserror::Error;

/// Which of the book's programs: book 3's Cornell box (`src/TheRestOfYourLife/main.cc`), or book 2's
/// final scene (`src/TheNextWeek/main.cc`, its `final_scene` chosen by the `switch`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BookProgram {
    Cornell,
    Book2Final,
}

impl BookProgram {
    /// The program's directory in a checkout of RayTracing/raytracing.github.io.
    pub fn dir(self) -> &'static str {
        match self {
            BookProgram::Cornell => "src/TheRestOfYourLife",
            BookProgram::Book2Final => "src/TheNextWeek",
        }
    }
}

/// The settings the copy is patched to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BookSettings {
    pub width: usize,
    pub spp: u64,
    pub max_depth: u32,
    pub seed: u32,
}

/// A `main.cc` that does not look like the book's.
#[derive(Debug, Error, PartialEq)]
pub enum PatchError {
    #[error(
        "{file}: expected exactly one line {pattern}, found {found} (is this the book's code?)"
    )]
    Pattern {
        file: String,
        pattern: String,
        found: usize,
    },
}

/// Replaces the one line whose trimmed text starts with `start` by `with` (keeping its indent).
fn replace_line(
    lines: &mut [String],
    file: &str,
    start: &str,
    with: impl Fn(&str) -> String,
) -> Result<(), PatchError> {
    let hits: Vec<usize> = lines
        .iter()
        .enumerate()
        .filter(|(_, l)| l.trim_start().starts_with(start))
        .map(|(i, _)| i)
        .collect();
    if hits.len() != 1 {
        return Err(PatchError::Pattern {
            file: file.into(),
            pattern: format!("starting `{start}`"),
            found: hits.len(),
        });
    }
    let line = &mut lines[hits[0]];
    let indent = &line[..line.len() - line.trim_start().len()];
    *line = format!("{indent}{}", with(line.trim_start()));
    Ok(())
}

/// The book's `main.cc` (text `src`, named `file` in errors) patched to `settings`.
pub fn patch_main(
    src: &str,
    file: &str,
    program: BookProgram,
    s: &BookSettings,
) -> Result<String, PatchError> {
    let mut lines: Vec<String> = src.lines().map(String::from).collect();
    match program {
        BookProgram::Cornell => {
            replace_line(&mut lines, file, "cam.image_width", |_| {
                format!("cam.image_width       = {};", s.width)
            })?;
            replace_line(&mut lines, file, "cam.samples_per_pixel", |_| {
                format!("cam.samples_per_pixel = {};", s.spp)
            })?;
            replace_line(&mut lines, file, "cam.max_depth", |_| {
                format!("cam.max_depth         = {};", s.max_depth)
            })?;
        }
        BookProgram::Book2Final => {
            replace_line(&mut lines, file, "switch (0)", |l| {
                l.replacen("(0)", "(9)", 1)
            })?;
            replace_line(&mut lines, file, "case 9:", |_| {
                format!(
                    "case 9:  final_scene({}, {}, {}); break;",
                    s.width, s.spp, s.max_depth
                )
            })?;
        }
    }
    replace_line(&mut lines, file, "int main() {", |_| {
        format!("int main() {{ srand({}u);", s.seed)
    })?;
    let mut out = String::from("#include <cstdlib>\n");
    for l in lines {
        out.push_str(&l);
        out.push('\n');
    }
    Ok(out)
}

/// The samples per pixel the book's camera takes for `spp`: book 3 stratifies the pixel into
/// `floor(sqrt(spp))^2` cells, one sample each; book 2 takes `spp`.
pub fn samples_taken(program: BookProgram, spp: u64) -> u64 {
    match program {
        BookProgram::Cornell => {
            let r = (spp as f64).sqrt() as u64;
            let r = (r.saturating_sub(1)..=r + 1)
                .rev()
                .find(|k| k * k <= spp)
                .unwrap_or(0);
            r * r
        }
        BookProgram::Book2Final => spp,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CORNELL: &str = "#include \"rtweekend.h\"\n\nint main() {\n    hittable_list world;\n    camera cam;\n\n    cam.aspect_ratio      = 1.0;\n    cam.image_width       = 600;\n    cam.samples_per_pixel = 100;\n    cam.max_depth         = 50;\n    cam.render(world, lights);\n}\n";

    const SETTINGS: BookSettings = BookSettings {
        width: 64,
        spp: 16,
        max_depth: 7,
        seed: 3,
    };

    #[test]
    fn the_cornell_constants_and_the_seed_are_set() {
        let out = patch_main(CORNELL, "main.cc", BookProgram::Cornell, &SETTINGS).unwrap();
        assert!(out.starts_with("#include <cstdlib>\n"));
        assert!(out.contains("\n    cam.image_width       = 64;\n"), "{out}");
        assert!(out.contains("\n    cam.samples_per_pixel = 16;\n"), "{out}");
        assert!(out.contains("\n    cam.max_depth         = 7;\n"), "{out}");
        assert!(out.contains("\nint main() { srand(3u);\n"), "{out}");
        assert!(out.contains("cam.aspect_ratio      = 1.0;"));
        assert_eq!(out.lines().count(), CORNELL.lines().count() + 1);
    }

    #[test]
    fn book2_final_is_chosen_and_sized() {
        let src = "int main() {\n    switch (0) {\n        case 9:  final_scene(800, 10000, 40); break;\n        default: final_scene(400,   250,  4); break;\n    }\n}\n";
        let out = patch_main(src, "main.cc", BookProgram::Book2Final, &SETTINGS).unwrap();
        assert!(out.contains("    switch (9) {\n"), "{out}");
        assert!(
            out.contains("        case 9:  final_scene(64, 16, 7); break;\n"),
            "{out}"
        );
        assert!(out.contains("default: final_scene(400,   250,  4)"));
    }

    #[test]
    fn a_main_that_is_not_the_books_is_refused() {
        let src = CORNELL.replace("    cam.max_depth         = 50;\n", "");
        let e = patch_main(&src, "x/main.cc", BookProgram::Cornell, &SETTINGS).unwrap_err();
        assert_eq!(
            e,
            PatchError::Pattern {
                file: "x/main.cc".into(),
                pattern: "starting `cam.max_depth`".into(),
                found: 0
            }
        );
        let twice = format!("{CORNELL}int main() {{\n}}\n");
        let e = patch_main(&twice, "m.cc", BookProgram::Cornell, &SETTINGS).unwrap_err();
        assert!(e.to_string().contains("found 2"), "{e}");
    }

    #[test]
    fn book3_stratifies_into_a_square_number_of_samples() {
        assert_eq!(samples_taken(BookProgram::Cornell, 16), 16);
        assert_eq!(samples_taken(BookProgram::Cornell, 100), 100);
        assert_eq!(samples_taken(BookProgram::Cornell, 20), 16);
        assert_eq!(samples_taken(BookProgram::Cornell, 1), 1);
        assert_eq!(samples_taken(BookProgram::Book2Final, 20), 20);
    }
}
