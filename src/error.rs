//! The one error type of the crate's constructors and `try_` functions.

use core::fmt;

/// Why an input was rejected (the list of the repository's `docs/models.md`, "Inputs that are not valid").
///
/// Variants that carry a `&'static str` name the offending parameter as the eval protocol and
/// the spec spell it (`"n"`, `"axis"`, `"verts"`, ...).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// A NaN or infinity in the named parameter.
    NotFinite(&'static str),
    /// The named direction parameter has zero length.
    ZeroLength(&'static str),
    /// A polygon with fewer than 3 vertices.
    TooFewVertices,
    /// A polygon with more vertices than the light's const-generic capacity.
    TooManyVertices {
        /// The capacity `N` of the polygon type.
        capacity: usize,
    },
    /// A polygon of zero area (collinear or coincident vertices), or a parallelogram light
    /// with `eu x ev = 0`.
    ZeroArea,
    /// A polygon whose vertices are not in one plane (to within 1e-6 of its size).
    NotPlanar,
    /// A polygon whose edges cross (not simple).
    NotSimple,
    /// A sphere radius that is not > 0.
    RadiusNotPositive,
    /// A shading point inside or on a sphere light.
    PointInsideSphere,
    /// A cap half-angle sigma outside [0, pi/2].
    SigmaOutOfRange,
    /// A disc half-angle alpha outside [0, pi].
    AlphaOutOfRange,
    /// A Phong exponent too large for the crate (more than [`crate::lobe::MAX_EXPONENT`], or
    /// [`crate::Real::MAX_PHONG_EXPONENT`] of the scalar type: 255 for the fixed-point type).
    ExponentOutOfRange,
    /// The named position parameter has a coordinate beyond
    /// [`crate::Real::COORDINATE_LIMIT`] of the scalar type (only the fixed-point type has a
    /// limit: 4, so that products of point differences stay inside its range), or beyond the
    /// world format's `2^30` ([`crate::WorldPoint::LIMIT`], every backend).
    OutOfRange(&'static str),
    /// A shading point on the segment of a line light (to within the precision of the scalar
    /// type: closer than `Real::TINY` times the light's distance scale).
    PointOnSegment,
    /// The scalar type cannot resolve the named position finely enough for the model's
    /// documented accuracy. Fixed point only: a shading point within the type's rounding of a
    /// polygon light's plane and over its face (or near its edges), where the value jumps from
    /// 0 (in the plane) to nearly the whole face just off it, and the type cannot tell which;
    /// and a shading point so close to a polygon light's vertex, or to an edge beside it, that
    /// the directions the model needs are not known to its accuracy (the limits of the polygon
    /// module's fixed-point section, README "Fixed point").
    Unresolved(&'static str),
    /// A line light's decay exponent k outside {0, 1, 2, 3}.
    DecayOutOfRange,
    /// An unnormalized value (a line light's `I ~ distance^-k`) too large for the scalar type.
    Overflow,
    /// The named parameter is not > 0 (superellipse sizes and roundness, falloff `d0` and
    /// zone edges).
    NotPositive(&'static str),
    /// The named parameter is negative (falloff `alpha`, the distance `z`).
    Negative(&'static str),
    /// Two parameters that must satisfy `low < high` do not (`a < A`, `b < B`,
    /// `znear < zfar`).
    NotOrdered {
        /// The parameter that must be the smaller.
        low: &'static str,
        /// The parameter that must be the larger.
        high: &'static str,
    },
    /// A distance falloff whose peak `M` is not > 1.
    PeakNotAboveOne,
    /// Two direction parameters that must not be parallel are (a light frame's `up` and
    /// `direction`).
    Parallel {
        /// The first parameter.
        a: &'static str,
        /// The second parameter.
        b: &'static str,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::NotFinite(p) => write!(f, "{p} is not finite (NaN or infinity)"),
            Error::ZeroLength(p) => write!(f, "{p} has zero length"),
            Error::TooFewVertices => f.write_str("polygon has fewer than 3 vertices"),
            Error::TooManyVertices { capacity } => {
                write!(
                    f,
                    "polygon has more than {capacity} vertices (the light's capacity)"
                )
            }
            Error::ZeroArea => f.write_str("polygon has zero area"),
            Error::NotPlanar => f.write_str("polygon is not planar (to within 1e-6 of its size)"),
            Error::NotSimple => f.write_str("polygon is not simple (edges cross)"),
            Error::RadiusNotPositive => f.write_str("sphere radius is not > 0"),
            Error::PointInsideSphere => f.write_str("shading point is inside or on the sphere"),
            Error::SigmaOutOfRange => f.write_str("sigma is outside [0, pi/2]"),
            Error::AlphaOutOfRange => f.write_str("alpha is outside [0, pi]"),
            Error::ExponentOutOfRange => f.write_str("Phong exponent m is too large"),
            Error::OutOfRange(p) => {
                write!(f, "{p} is outside the coordinate range (|x| <= 4 for the fixed-point type's own coordinates, |x| < 2^30 for world coordinates)")
            }
            Error::PointOnSegment => f.write_str("shading point is on the segment"),
            Error::Unresolved(p) => write!(
                f,
                "{p} is too close to the light's plane or boundary for the scalar type's precision: the value is not resolved (fixed point)"
            ),
            Error::DecayOutOfRange => f.write_str("decay k is outside {0, 1, 2, 3}"),
            Error::Overflow => f.write_str("the value overflows the scalar type"),
            Error::NotPositive(p) => write!(f, "{p} is not > 0"),
            Error::Negative(p) => write!(f, "{p} is negative"),
            Error::NotOrdered { low, high } => write!(f, "{low} is not < {high}"),
            Error::PeakNotAboveOne => f.write_str("falloff peak M is not > 1"),
            Error::Parallel { a, b } => write!(f, "{a} is parallel to {b}"),
        }
    }
}

impl core::error::Error for Error {}
