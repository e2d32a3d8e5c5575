//! The indices a scene's parts refer to each other by, each its own type so that a material index is
//! never taken for a texture's or a group's.

/// Index of a group (a list of objects with its own BVH) in the scene; group 0 is the world.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct GroupId(pub u32);

/// Index of a material in the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub struct MaterialId(pub u32);

impl MaterialId {
    /// The material of a shape that is only an importance target (a shape to aim at, not placed in the
    /// scene): no material, so the target never counts as an emitter.
    pub const NONE: MaterialId = MaterialId(u32::MAX);

    /// The position in the scene's materials.
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Index of a texture in the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct TextureId(pub u32);

impl TextureId {
    /// The position in the scene's textures.
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }
}
