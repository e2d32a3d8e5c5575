//! `rtl render --explain`: what the renderer will simulate for this scene and why, from the scene's
//! features (each effect used or skipped, with the reason), before any work starts.

use super::Loaded;
use rtl_render::hit_tier::HitTier;
use rtl_render::integrator::Strategy;
use rtl_render::paths8::{LANES, PACKETS};
use rtl_render::render::{RenderSettings, Renderer};
use rtl_render::scene::Scene;
use rtl_render::tier_race::TierRace;

fn yes_no(on: bool, yes: &str, no: &str) -> String {
    if on {
        format!("used    {yes}")
    } else {
        format!("skipped {no}")
    }
}

/// `--explain`: which effects the scene calls for and which the renderer therefore simulates or
/// skips, the strategy and the image's settings, printed before any work starts.
pub(super) fn explain(
    l: &Loaded,
    scene: &Scene,
    settings: &RenderSettings,
    spp: u64,
    no_lanes: bool,
    race: Option<&TierRace>,
) {
    let f = scene.features;
    println!("scene {}: {}", l.name, l.description);
    println!(
        "  lens / defocus blur : {}",
        yes_no(
            f.defocus,
            "(thin lens: 2 random numbers per camera ray)",
            "(pinhole camera: no lens samples drawn)"
        )
    );
    println!(
        "  motion blur / time  : {}",
        yes_no(
            f.motion,
            "(something moves: 1 time sample per camera ray)",
            "(nothing moves: no time samples drawn)"
        )
    );
    println!(
        "  participating media : {}",
        yes_no(
            f.media > 0,
            &if f.media_in_pieces == 0 {
                format!("({} constant media)", f.media)
            } else {
                format!(
                    "({} constant media; {} of them in several pieces or not convex: every \
                     stretch a ray crosses is taken, at two more traversals a stretch)",
                    f.media, f.media_in_pieces
                )
            },
            "(no media: nothing tested or sampled for them)"
        )
    );
    println!(
        "  textures            : {}",
        yes_no(
            f.textures > 0,
            &format!("({} non-constant textures)", f.textures),
            "(plain colours only: no texture lookups)"
        )
    );
    let (tier, best) = (HitTier::current(), HitTier::detected());
    // the tiers' keys, as the lanes' line names them
    let tier_keys = match race {
        Some(r) => format!("{} or {}", r.tiers()[0].key(), r.tiers()[1].key()),
        None => tier.key().to_string(),
    };
    if let Some(r) = race {
        let [a, b] = r.tiers();
        println!(
            "  intersection        : {} or {}, whichever is faster here: timed side by side on the \
             render's first passes, then the faster runs the rest (the image is the same; \
             --hit-tier names one)",
            a.key(),
            b.key()
        );
    } else if tier == best {
        println!("  intersection        : {}", tier.name());
    } else if tier == HitTier::preferred() {
        println!(
            "  intersection        : {} (this processor also runs {}, slower on Intel cores: \
             --hit-tier {} runs it)",
            tier.name(),
            best.key(),
            best.key()
        );
    } else {
        println!(
            "  intersection        : {} (--hit-tier; the best this processor runs is {})",
            tier.name(),
            best.key()
        );
    }
    let lanes = Renderer::new(scene, *settings);
    println!(
        "  paths               : {}",
        if no_lanes && lanes.paths_in_lanes() {
            "one at a time (--no-lanes)".to_string()
        } else if lanes.paths_in_lanes() {
            format!(
                "{} side by side in the vector lanes ({}), in {} packets of {} whose rays are \
                 intersected together{}",
                PACKETS * LANES,
                tier_keys,
                PACKETS,
                LANES,
                match (
                    settings.strategy.mis_options().is_some(),
                    lanes.lambertian_vertex_in_lanes().is_some(),
                    lanes.glass_vertex_in_lanes().is_some(),
                    lanes.mixture_in_lanes().is_some(),
                ) {
                    (true, _, _, _) if lanes.mis_vertex_in_lanes().is_some() => {
                        " (mis: a vertex's shadow ray in one round, the path's next ray in the \
                         next; the vertices on Lambertian quads, light sample and material \
                         sample, computed in the lanes, eight at a time)"
                    }
                    (true, _, _, _) => {
                        " (mis: a vertex's shadow ray in one round, the path's next ray in the \
                         next)"
                    }
                    (false, true, true, _) => {
                        "; the vertices on Lambertian quads (with the mixture's directions) and \
                         on glass spheres computed whole in the lanes, eight at a time"
                    }
                    (false, true, false, _) => {
                        "; the vertices on Lambertian quads (with the mixture's directions) \
                         computed whole in the lanes, eight at a time"
                    }
                    (false, false, _, true) => {
                        " and the mixture's directions drawn together at Lambertian points"
                    }
                    _ => "",
                }
            )
        } else if settings.strategy.mis_options().is_some() && scene.features.media > 0 {
            "one at a time (mis through media: shadow rays record the media they cross, paths \
             may scatter in them)"
                .to_string()
        } else if !scene.hits_eight_at_once(rtl_render::scene::GroupId(0)) {
            if HitTier::current() == HitTier::Portable {
                "one at a time (no AVX2 tier)".to_string()
            } else {
                "one at a time (the scene is not one small group of several objects)".to_string()
            }
        } else {
            "one at a time".to_string()
        }
    );
    if f.flattened_instances > 0 {
        println!(
            "  instances           : {} placed in world space at build time (rigid, of non-emitting \
             quads: tested in their parent's quad packets, no ray moved into their frame; where \
             eight rays are tested at once, an instance of four quads or more only for the rays \
             that enter its box)",
            f.flattened_instances
        );
    }
    println!(
        "  emitters            : {}",
        if f.emitters == 0 {
            "none (light comes from the background)".to_string()
        } else {
            format!(
                "{} ({})",
                f.emitters,
                if f.one_sided_emitters {
                    "one-sided"
                } else {
                    "two-sided"
                }
            )
        }
    );
    println!(
        "  importance targets  : {}",
        if f.targets == 0 {
            "none".to_string()
        } else {
            format!(
                "{} listed; {}",
                f.targets,
                match settings.strategy {
                    Strategy::Uniform | Strategy::Cosine => format!(
                        "not used by the '{}' strategy (book-2 scattering)",
                        settings.strategy.name()
                    ),
                    Strategy::Light => "sampled alone: biased (indirect light is missed)".into(),
                    Strategy::Mixture => format!(
                        "mixed with the material's density, a share of {} towards the targets",
                        settings.mixture_weight
                    ),
                    Strategy::Mis(_) => "emitters by next-event estimation, the others \
                        mixed with the material's density"
                        .into(),
                }
            )
        }
    );
    let spherical = settings
        .strategy
        .mis_options()
        .is_some_and(|o| o.spherical_rectangles);
    let lights = rtl_render::lights::Lights::new(scene, spherical);
    println!(
        "  next-event estimation: {}",
        match settings.strategy {
            Strategy::Mis(_) => format!(
                "shadow rays to every emitter, listed or not, through media with their \
                 transmittance: {}",
                lights.describe_emitters()
            ),
            s => format!("not used by the '{}' strategy", s.name()),
        }
    );
    println!(
        "  manifold connections: {}",
        match settings.strategy {
            Strategy::Mis(o) if o.manifold => lights.manifold.describe(),
            Strategy::Mis(_) => "off (--no-manifold)".to_string(),
            s => format!("not used by the '{}' strategy", s.name()),
        }
    );
    let background = match scene.background {
        rtl_render::scene::Background::Solid(c) => format!("solid ({}, {}, {})", c.x, c.y, c.z),
        rtl_render::scene::Background::Sky => "book 1's sky gradient".to_string(),
    };
    println!("  background          : {background}");
    println!(
        "  strategy            : {} ({})",
        settings.strategy.name(),
        settings.strategy.description()
    );
    println!(
        "  max depth           : {} intersections per path",
        settings.max_depth
    );
    println!(
        "  image               : {} wide, {spp} samples per pixel, seed {}",
        settings.width, settings.seed
    );
}
