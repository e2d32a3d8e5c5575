//! The indices a scene's parts refer to each other by, each its own type so that a material index is
//! never taken for a texture's or a group's.

/// Index of a group (a list of objects with its own BVH) in the scene; group 0 is the world.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct GroupId(pub u32);

/// Index of a material in the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct MaterialId(pub u32);

/// Index of a texture in the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct TextureId(pub u32);
