//! The book's C++ program, patched in a scratch copy to the comparison's settings.
//!
//! The book's `main.cc` compiles its image width, samples per pixel and depth in, and its
//! `random_double` is `rand()`, never seeded. The harness writes a patched copy of `main.cc` into its
//! scratch directory (its headers are still read from the checkout, by `-I`): the copy sets those
//! three constants and seeds `rand()` with the run's seed before rendering, so that two runs are
//! independent renders of the same scene. The checkout itself is never modified, and none of its
//! code is part of this project.
//!
//! Book 2's final scene draws its ground's heights, its 1000 spheres and its Perlin tables from that
//! same `rand()` while it is built. Seeded first thing in `main`, two runs would render two different
//! scenes, and the difference of their images, which the noise constant is made from, would hold the
//! difference of the scenes too: a share that does not fall with the samples, so the constant would
//! grow with them (at 200 x 200: 0.82 at 16 spp, 1.62 at 256). So that program builds its scene
//! from `srand(1)`, the state an unseeded `rand()` starts in (the book's own scene), and is seeded
//! with the run's seed just before `cam.render`.

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

/// Replaces the first line whose trimmed text starts with `start` after the line that starts with
/// `function` (a function's header), keeping its indent.
fn replace_line_in(
    lines: &mut [String],
    file: &str,
    function: &str,
    start: &str,
    with: impl Fn(&str) -> String,
) -> Result<(), PatchError> {
    let not_found = |pattern: String| PatchError::Pattern {
        file: file.into(),
        pattern,
        found: 0,
    };
    let header = lines
        .iter()
        .position(|l| l.trim_start().starts_with(function))
        .ok_or_else(|| not_found(format!("starting `{function}`")))?;
    let at = lines[header + 1..]
        .iter()
        .position(|l| l.trim_start().starts_with(start))
        .ok_or_else(|| not_found(format!("starting `{start}` after `{function}`")))?;
    let line = &mut lines[header + 1 + at];
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
            replace_line_in(
                &mut lines,
                file,
                "void final_scene(",
                "cam.render(world);",
                |_| format!("srand({}u); cam.render(world);", s.seed),
            )?;
        }
    }
    // Book 2's final scene is built from rand()'s unseeded state whatever the seed (see the module's
    // notes) and seeded before its render; book 3's Cornell box draws nothing while it is built.
    let main_seed = match program {
        BookProgram::Cornell => s.seed,
        BookProgram::Book2Final => 1,
    };
    replace_line(&mut lines, file, "int main() {", |_| {
        format!("int main() {{ srand({main_seed}u);")
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

    const BOOK2: &str = "void cornell_smoke() {\n    cam.render(world);\n}\n\nvoid final_scene(int image_width, int samples_per_pixel, int max_depth) {\n    auto y1 = random_double(1,101);\n    cam.render(world);\n}\n\nint main() {\n    switch (0) {\n        case 9:  final_scene(800, 10000, 40); break;\n        default: final_scene(400,   250,  4); break;\n    }\n}\n";

    #[test]
    fn book2_final_is_chosen_and_sized() {
        let out = patch_main(BOOK2, "main.cc", BookProgram::Book2Final, &SETTINGS).unwrap();
        assert!(out.contains("    switch (9) {\n"), "{out}");
        assert!(
            out.contains("        case 9:  final_scene(64, 16, 7); break;\n"),
            "{out}"
        );
        assert!(out.contains("default: final_scene(400,   250,  4)"));
    }

    /// The scene is drawn from the same numbers whatever the seed; only its render is seeded.
    #[test]
    fn book2_final_builds_one_scene_and_seeds_its_render() {
        let with_seed = |seed| {
            patch_main(
                BOOK2,
                "main.cc",
                BookProgram::Book2Final,
                &BookSettings { seed, ..SETTINGS },
            )
            .unwrap()
        };
        let (a, b) = (with_seed(3), with_seed(4));
        assert!(a.contains("\nint main() { srand(1u);\n"), "{a}");
        assert!(b.contains("\nint main() { srand(1u);\n"), "{b}");
        assert!(
            a.contains("auto y1 = random_double(1,101);\n    srand(3u); cam.render(world);\n"),
            "{a}"
        );
        // only final_scene's render is seeded
        assert!(
            a.contains("void cornell_smoke() {\n    cam.render(world);\n"),
            "{a}"
        );
        let differ: Vec<_> = a.lines().zip(b.lines()).filter(|(x, y)| x != y).collect();
        assert_eq!(
            differ,
            [(
                "    srand(3u); cam.render(world);",
                "    srand(4u); cam.render(world);"
            )]
        );
        // a final_scene without its render call is not the book's
        let e = patch_main(
            &BOOK2.replace("    cam.render(world);\n}\n\nint", "}\n\nint"),
            "m.cc",
            BookProgram::Book2Final,
            &SETTINGS,
        )
        .unwrap_err();
        assert!(e.to_string().contains("after `void final_scene(`"), "{e}");
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
