//! What plane geometry needs of nalgebra's [`Vector2`] beyond nalgebra itself.
//!
//! The 2-D cross product is nalgebra's own `a.perp(&b)` (`a.x * b.y - a.y * b.x`),
//! the dot product `a.dot(&b)` and the squared length `norm_squared()`.

use nalgebra::Vector2;

/// A vector of the plane, metres or a unit direction.
pub trait PlaneVector: Sized {
    /// Unit vector at angle `a`, radians counter-clockwise from +x.
    fn from_angle(a: f64) -> Self;

    /// The length by `f64::hypot`. nalgebra's `norm()` is the square root of
    /// the sum of squares, which may differ in the last bit: the simulator's
    /// runs (and so every trace and experiment) are measured with this one.
    fn hypot(&self) -> f64;

    /// Rotated a quarter turn counter-clockwise.
    fn rotated_left(&self) -> Self;

    /// Angle from +x, radians in [-pi, pi] (`atan2`).
    fn polar_angle(&self) -> f64;

    /// Whether both components are finite.
    fn is_finite(&self) -> bool;
}

impl PlaneVector for Vector2<f64> {
    fn from_angle(a: f64) -> Self {
        let (s, c) = a.sin_cos();
        Vector2::new(c, s)
    }

    fn hypot(&self) -> f64 {
        self.x.hypot(self.y)
    }

    fn rotated_left(&self) -> Self {
        Vector2::new(-self.y, self.x)
    }

    fn polar_angle(&self) -> f64 {
        self.y.atan2(self.x)
    }

    fn is_finite(&self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }
}

/// Serde for a [`Point2`](nalgebra::Point2) or [`Vector2`] field as the table
/// `{ x, y }` (`#[serde(with = "ilmr_geometry::xy")]`): the format the
/// simulator's own vector type had, where nalgebra's would be a sequence.
pub mod xy {
    use nalgebra::{Point2, Vector2};
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    /// The table as written. Named as the simulator's type was, so that a
    /// format that records struct names writes what it wrote before.
    #[derive(Serialize, Deserialize)]
    #[serde(rename = "Vec2")]
    struct Xy {
        x: f64,
        y: f64,
    }

    /// A point or vector of the plane, by its two coordinates.
    pub trait Coordinates: Sized {
        fn xy(&self) -> (f64, f64);
        fn from_xy(x: f64, y: f64) -> Self;
    }

    impl Coordinates for Point2<f64> {
        fn xy(&self) -> (f64, f64) {
            (self.x, self.y)
        }
        fn from_xy(x: f64, y: f64) -> Self {
            Point2::new(x, y)
        }
    }

    impl Coordinates for Vector2<f64> {
        fn xy(&self) -> (f64, f64) {
            (self.x, self.y)
        }
        fn from_xy(x: f64, y: f64) -> Self {
            Vector2::new(x, y)
        }
    }

    pub fn serialize<T: Coordinates, S: Serializer>(v: &T, s: S) -> Result<S::Ok, S::Error> {
        Xy::of(v).serialize(s)
    }

    pub fn deserialize<'de, T: Coordinates, D: Deserializer<'de>>(d: D) -> Result<T, D::Error> {
        Xy::deserialize(d).map(Xy::into)
    }

    impl Xy {
        fn of<T: Coordinates>(v: &T) -> Xy {
            let (x, y) = v.xy();
            Xy { x, y }
        }

        fn into<T: Coordinates>(self) -> T {
            T::from_xy(self.x, self.y)
        }
    }

    /// A list of them, as a list of tables.
    pub mod seq {
        use super::{Coordinates, Xy};
        use serde::{Deserialize, Deserializer, Serialize, Serializer};

        pub fn serialize<T: Coordinates, S: Serializer>(v: &[T], s: S) -> Result<S::Ok, S::Error> {
            v.iter().map(Xy::of).collect::<Vec<_>>().serialize(s)
        }

        pub fn deserialize<'de, T: Coordinates, D: Deserializer<'de>>(
            d: D,
        ) -> Result<Vec<T>, D::Error> {
            Ok(Vec::<Xy>::deserialize(d)?
                .into_iter()
                .map(Xy::into)
                .collect())
        }
    }

    /// Two of them (a segment's ends), as a pair of tables.
    pub mod pair {
        use super::{Coordinates, Xy};
        use serde::{Deserialize, Deserializer, Serialize, Serializer};

        pub fn serialize<T: Coordinates, S: Serializer>(
            v: &(T, T),
            s: S,
        ) -> Result<S::Ok, S::Error> {
            (Xy::of(&v.0), Xy::of(&v.1)).serialize(s)
        }

        pub fn deserialize<'de, T: Coordinates, D: Deserializer<'de>>(
            d: D,
        ) -> Result<(T, T), D::Error> {
            let (a, b) = <(Xy, Xy)>::deserialize(d)?;
            Ok((a.into(), b.into()))
        }
    }

    /// A list of pairs.
    pub mod pairs {
        use super::{Coordinates, Xy};
        use serde::{Deserialize, Deserializer, Serialize, Serializer};

        pub fn serialize<T: Coordinates, S: Serializer>(
            v: &[(T, T)],
            s: S,
        ) -> Result<S::Ok, S::Error> {
            v.iter()
                .map(|(a, b)| (Xy::of(a), Xy::of(b)))
                .collect::<Vec<_>>()
                .serialize(s)
        }

        pub fn deserialize<'de, T: Coordinates, D: Deserializer<'de>>(
            d: D,
        ) -> Result<Vec<(T, T)>, D::Error> {
            let v = Vec::<(Xy, Xy)>::deserialize(d)?;
            Ok(v.into_iter().map(|(a, b)| (a.into(), b.into())).collect())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point2;
    use serde::{Deserialize, Serialize};

    #[test]
    fn the_helpers_keep_the_simulators_arithmetic() {
        let tiny = 2.0_f64.powi(-600);
        let v = Vector2::new(3.0 * tiny, 4.0 * tiny);
        // Squares underflow: the sum-of-squares norm loses what hypot keeps.
        assert_eq!(v.hypot(), 5.0 * tiny);
        assert_eq!(v.norm(), 0.0);
        let (s, c) = 0.7_f64.sin_cos();
        assert_eq!(Vector2::from_angle(0.7), Vector2::new(c, s));
        assert_eq!(
            Vector2::new(1.0, 2.0).rotated_left(),
            Vector2::new(-2.0, 1.0)
        );
        assert_eq!(Vector2::new(-1.0, 0.0).polar_angle(), std::f64::consts::PI);
        assert!(Vector2::new(1.0, -2.0).is_finite());
        assert!(!Vector2::new(f64::NAN, 0.0).is_finite());
        assert!(!Vector2::new(0.0, f64::NEG_INFINITY).is_finite());
        // nalgebra's perpendicular product is the 2-D cross product: positive
        // when the second vector lies to the left of the first.
        assert_eq!(Vector2::new(1.0, 0.0).perp(&Vector2::new(0.0, 2.0)), 2.0);
    }

    #[derive(Debug, PartialEq, Serialize, Deserialize)]
    struct Mounted {
        #[serde(with = "xy")]
        at: Point2<f64>,
        #[serde(with = "xy")]
        half: Vector2<f64>,
        #[serde(with = "xy::seq")]
        path: Vec<Point2<f64>>,
        #[serde(with = "xy::pair")]
        ends: (Point2<f64>, Point2<f64>),
        #[serde(with = "xy::pairs")]
        pieces: Vec<(Point2<f64>, Point2<f64>)>,
    }

    #[test]
    fn points_and_vectors_are_written_as_x_y_tables() {
        let m = Mounted {
            at: Point2::new(0.85, -0.1),
            half: Vector2::new(0.5, 0.25),
            path: vec![Point2::new(1.0, 2.0), Point2::new(3.0, 4.5)],
            ends: (Point2::new(0.0, 0.0), Point2::new(2.0, 0.0)),
            pieces: vec![(Point2::new(0.0, 0.0), Point2::new(0.5, 0.0))],
        };
        let text = serde_json::to_string(&m).unwrap_or_default();
        assert_eq!(
            text,
            concat!(
                r#"{"at":{"x":0.85,"y":-0.1},"half":{"x":0.5,"y":0.25},"#,
                r#""path":[{"x":1.0,"y":2.0},{"x":3.0,"y":4.5}],"#,
                r#""ends":[{"x":0.0,"y":0.0},{"x":2.0,"y":0.0}],"#,
                r#""pieces":[[{"x":0.0,"y":0.0},{"x":0.5,"y":0.0}]]}"#
            )
        );
        assert_eq!(serde_json::from_str::<Mounted>(&text).ok(), Some(m));
        let no_y = text.replacen(r#","y":-0.1"#, "", 1);
        assert!(serde_json::from_str::<Mounted>(&no_y).is_err());
    }
}
