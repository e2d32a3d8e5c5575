//! Rigid instances flattened into their parent at build time: book 2's `translate(rotate_y(box))`
//! placed in a small group (book 3's Cornell box) becomes six quads in world space, `Q' = R Q + t`,
//! `u' = R u`, `v' = R v`, tested in the parent's packets with no ray moved into the instance's frame
//! and no record moved back.
//!
//! This is a change of rounding, not of geometry: the world-space quad is the placed quad up to the
//! rounding of `R Q + t`, `R u` and `R v` (a few ulps of their magnitude), and its hits are computed in
//! world space, so their `t`, point and normal differ from the instance's in the last bits
//! (`crates/render/tests/flatten.rs` bounds the difference). Each flattened quad's error bound is its
//! own, as for any world-space quad ([`Quad::new`]).
//!
//! Only what keeps every other part of the scene as it was is flattened: instances of groups made of
//! quads alone, none of them emitting (the emitters keep their place in the light list, collected
//! through their instance), into a group that holds no medium and fits the flat small form with them
//! ([`SMALL_QUADS`], [`SMALL_OTHERS`]).

use crate::material::Material;
use crate::scene::Object;
use crate::shapes::Quad;
use crate::transform::Transform;
use crate::traversal::{SMALL_OTHERS, SMALL_QUADS};

/// The quads of `inner` (a group's objects) placed by `transform` in world space, if `inner` is made
/// of non-emitting quads alone (`None` otherwise, or if a placed quad would be degenerate).
pub fn placed_quads(
    transform: &Transform,
    inner: &[Object],
    materials: &[Material],
) -> Option<Vec<Quad>> {
    inner
        .iter()
        .map(|o| match o {
            Object::Quad(q)
                if matches!(
                    materials.get(q.material.index()),
                    Some(m) if !matches!(m, Material::DiffuseLight { .. })
                ) =>
            {
                Quad::new(
                    transform.point(q.q),
                    transform.vector(q.u),
                    transform.vector(q.v),
                    q.material,
                )
            }
            _ => None,
        })
        .collect()
}

/// `objects` (a group's, in the builder's order) with every rigid instance of a group of
/// non-emitting quads replaced by its quads in world space, in its place, if the group then fits the
/// flat small form and holds no medium; `objects` unchanged otherwise. `groups[g]` are the objects of
/// group `g`.
pub fn flatten_instances(
    objects: &[Object],
    groups: &[Vec<Object>],
    materials: &[Material],
) -> Vec<Object> {
    flatten_instances_marked(objects, groups, materials).0
}

/// [`flatten_instances`], and beside each object the instance it came from, if flattened (the
/// flattened instances numbered from 0 in their order in `objects`): the quads that the lanes test
/// behind their instance's box ([`crate::ray8::Cluster`]).
pub fn flatten_instances_marked(
    objects: &[Object],
    groups: &[Vec<Object>],
    materials: &[Material],
) -> (Vec<Object>, Vec<Option<u32>>) {
    let unchanged = || (objects.to_vec(), vec![None; objects.len()]);
    if objects.iter().any(|o| matches!(o, Object::Medium(_))) {
        return unchanged();
    }
    let mut out = Vec::with_capacity(objects.len());
    let mut from = Vec::with_capacity(objects.len());
    let mut flattened = 0;
    for o in objects {
        match o {
            Object::Instance { transform, group } => {
                match groups
                    .get(group.0 as usize)
                    .and_then(|inner| placed_quads(transform, inner, materials))
                {
                    Some(quads) => {
                        from.extend(quads.iter().map(|_| Some(flattened)));
                        out.extend(quads.into_iter().map(Object::Quad));
                        flattened += 1;
                    }
                    None => {
                        out.push(*o);
                        from.push(None);
                    }
                }
            }
            _ => {
                out.push(*o);
                from.push(None);
            }
        }
    }
    let quads = out.iter().filter(|o| matches!(o, Object::Quad(_))).count();
    if flattened == 0 || quads > SMALL_QUADS || out.len() - quads > SMALL_OTHERS {
        return unchanged();
    }
    (out, from)
}
