//! Rigid transforms: a rotation then a translation, the instances of book 2 (`translate(rotate_y(..))`),
//! with their inverses for rays and their action on bounding boxes.

use crate::aabb::Aabb;
use crate::vec::{Point3, Vec3};
use glam::DMat3;

/// A rigid transform `x -> R x + t` (rotation then translation), as book 2's `translate(rotate_y(..))`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Transform {
    pub rotation: DMat3,
    pub translation: Vec3,
}

impl Transform {
    pub const IDENTITY: Transform = Transform {
        rotation: DMat3::IDENTITY,
        translation: Vec3::ZERO,
    };

    /// Rotation by `degrees` about +y: `x' = cos x + sin z`, `z' = -sin x + cos z`.
    pub fn rotate_y(degrees: f64) -> Self {
        Transform {
            rotation: DMat3::from_rotation_y(degrees.to_radians()),
            translation: Vec3::ZERO,
        }
    }

    pub fn translate(offset: Vec3) -> Self {
        Transform {
            rotation: DMat3::IDENTITY,
            translation: offset,
        }
    }

    /// This transform followed by `next`.
    pub fn then(self, next: Transform) -> Self {
        Transform {
            rotation: next.rotation * self.rotation,
            translation: next.rotation * self.translation + next.translation,
        }
    }

    #[inline]
    pub fn point(&self, p: Point3) -> Point3 {
        self.rotation * p + self.translation
    }

    #[inline]
    pub fn vector(&self, v: Vec3) -> Vec3 {
        self.rotation * v
    }

    /// The inverse map of a point (`R^T (p - t)`, rotations being orthogonal).
    #[inline]
    pub fn inverse_point(&self, p: Point3) -> Point3 {
        self.rotation.transpose() * (p - self.translation)
    }

    #[inline]
    pub fn inverse_vector(&self, v: Vec3) -> Vec3 {
        self.rotation.transpose() * v
    }

    /// The bounding box of a transformed box (its eight transformed corners).
    pub fn bounds(&self, b: &Aabb) -> Aabb {
        let mut out = Aabb::EMPTY;
        for i in 0..8 {
            let c = Vec3::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            );
            out = out.include(self.point(c));
        }
        out.padded()
    }
}
