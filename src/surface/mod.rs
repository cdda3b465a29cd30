//! The surface core: validated B-spline/NURBS surfaces (tensor products over two knot
//! vectors, in every knot form the curves accept, periodic in either direction), their
//! evaluation with partials, normals and curvature, iso-curves, knot insertion, splitting,
//! closest points and certified meshes.
//!
//! Pure geometry, like [`crate::spline`], and built on it one direction at a time: a
//! direction's knots are a curve's knots (checked by the same rules), the curves through the
//! net's columns and rows carry every operation in `u` and in `v`, and the numerics (de Boor's
//! hodographs, blossoms, Bernstein bounds) are the curves' own.

mod bernstein2;
mod cells;
mod closest;
mod differential;
pub mod edit;
mod eval;
mod iso;
mod minimise;
mod patches;
mod refine;
#[allow(clippy::module_inception)]
mod surface;
mod tessellate;
mod validate;

pub use closest::{
    COORDINATE_ROUNDING, MAX_SUBDIVISIONS, SURFACE_CLOSEST_TOLERANCE, SurfaceClosestPoint,
    SurfaceClosestSearch, SurfaceRangeError,
};
pub use differential::{
    Curvature, Inward, NORMAL_DEGENERACY, NormalKind, UMBILIC_TOLERANCE, curvature, unit_normal,
};
pub use eval::{MAX_PARTIAL_ORDER, Partials};
pub use refine::{SurfaceInsertError, SurfaceSplitError};
pub use surface::{Axis, Direction, Surface};
pub use tessellate::{Mesh, TessellationError};
pub use validate::{SurfaceError, SurfaceField, SurfaceLimits};
