//! ROS 2 message types, in the order and with the widths of their `.msg` definitions
//! (ROS 2 Humble to Rolling: these messages have not changed). Field names follow ROS,
//! so that a reader of the ROS docs finds them.

use serde::{Deserialize, Serialize};

use crate::definition;

/// A message type and the name DDS knows it by (`pkg::msg::dds_::Name_`, as rosidl
/// generates it).
pub trait RosMessage: Serialize + for<'de> Deserialize<'de> {
    const DDS_TYPE_NAME: &'static str;
    /// The type as ROS 2 names it (`nav_msgs/msg/Odometry`).
    const ROS_TYPE: &'static str;
    /// Its `.msg` definition with those it uses (`definition.rs`).
    const DEFINITION: &'static str;
}

macro_rules! ros_message {
    ($ty:ident, $pkg:literal, $name:literal, $definition:expr) => {
        impl RosMessage for $ty {
            const DDS_TYPE_NAME: &'static str = concat!($pkg, "::msg::dds_::", $name, "_");
            const ROS_TYPE: &'static str = concat!($pkg, "/msg/", $name);
            const DEFINITION: &'static str = $definition;
        }
    };
}

/// `builtin_interfaces/Time`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Time {
    pub sec: i32,
    pub nanosec: u32,
}

impl Time {
    /// Seconds since the clock's epoch, as ILMR's clocks count them; a time before
    /// the epoch or beyond 2038 is clamped, as ROS 2's `int32` seconds are.
    pub fn from_secs(t: f64) -> Time {
        if !t.is_finite() || t <= 0.0 {
            return Time::default();
        }
        let sec = t.floor().min(f64::from(i32::MAX));
        let nanosec = ((t - sec) * 1e9).round().min(999_999_999.0);
        Time {
            sec: sec as i32,
            nanosec: nanosec as u32,
        }
    }

    pub fn as_secs(self) -> f64 {
        f64::from(self.sec) + f64::from(self.nanosec) * 1e-9
    }
}

/// `std_msgs/Header`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Header {
    pub stamp: Time,
    pub frame_id: String,
}
ros_message!(Header, "std_msgs", "Header", definition::HEADER);

/// `geometry_msgs/Vector3`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Vector3 {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// `geometry_msgs/Twist`: what `cmd_vel` carries.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Twist {
    pub linear: Vector3,
    pub angular: Vector3,
}
ros_message!(Twist, "geometry_msgs", "Twist", definition::TWIST);

/// `geometry_msgs/Point`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Point {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// `geometry_msgs/Quaternion`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Quaternion {
    pub x: f64,
    pub y: f64,
    pub z: f64,
    pub w: f64,
}

impl Default for Quaternion {
    fn default() -> Self {
        Quaternion::from_yaw(0.0)
    }
}

impl Quaternion {
    /// A rotation about z by `yaw` radians: a ground robot's heading.
    pub fn from_yaw(yaw: f64) -> Quaternion {
        let (s, c) = (yaw / 2.0).sin_cos();
        Quaternion {
            x: 0.0,
            y: 0.0,
            z: s,
            w: c,
        }
    }

    /// The heading about z, radians in (-pi, pi]; roll and pitch are ignored.
    pub fn yaw(&self) -> f64 {
        let siny = 2.0 * (self.w * self.z + self.x * self.y);
        let cosy = 1.0 - 2.0 * (self.y * self.y + self.z * self.z);
        siny.atan2(cosy)
    }
}

/// `geometry_msgs/Pose`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Pose {
    pub position: Point,
    pub orientation: Quaternion,
}

/// A 6x6 covariance, row-major, as the `float64[36]` of ROS 2 messages: a fixed array,
/// which CDR writes without a length (serde derives arrays up to 32 only).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Covariance(pub [f64; 36]);

impl Default for Covariance {
    fn default() -> Self {
        Covariance([0.0; 36])
    }
}

impl Serialize for Covariance {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeTuple;
        let mut t = s.serialize_tuple(36)?;
        for v in &self.0 {
            t.serialize_element(v)?;
        }
        t.end()
    }
}

impl<'de> Deserialize<'de> for Covariance {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = Covariance;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("36 float64 values")
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<Covariance, A::Error> {
                let mut out = [0.0; 36];
                for (i, slot) in out.iter_mut().enumerate() {
                    *slot = seq
                        .next_element()?
                        .ok_or_else(|| serde::de::Error::invalid_length(i, &self))?;
                }
                Ok(Covariance(out))
            }
        }
        d.deserialize_tuple(36, Visitor)
    }
}

/// `geometry_msgs/PoseWithCovariance`: row-major 6x6 over x, y, z and the rotations.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct PoseWithCovariance {
    pub pose: Pose,
    pub covariance: Covariance,
}

/// `geometry_msgs/TwistWithCovariance`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct TwistWithCovariance {
    pub twist: Twist,
    pub covariance: Covariance,
}

/// `nav_msgs/Odometry`: the pose in `header.frame_id` (`odom`), the velocity in
/// `child_frame_id` (`base_link`).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Odometry {
    pub header: Header,
    pub child_frame_id: String,
    pub pose: PoseWithCovariance,
    pub twist: TwistWithCovariance,
}
ros_message!(Odometry, "nav_msgs", "Odometry", definition::ODOMETRY);

/// `sensor_msgs/LaserScan`: angles in radians counter-clockwise from the scanner's x
/// axis, ranges in metres (outside `range_min..range_max`: no return).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct LaserScan {
    pub header: Header,
    pub angle_min: f32,
    pub angle_max: f32,
    pub angle_increment: f32,
    pub time_increment: f32,
    pub scan_time: f32,
    pub range_min: f32,
    pub range_max: f32,
    pub ranges: Vec<f32>,
    pub intensities: Vec<f32>,
}
ros_message!(
    LaserScan,
    "sensor_msgs",
    "LaserScan",
    definition::LASER_SCAN
);

/// `sensor_msgs/BatteryState` (NaN where unmeasured, as the message defines).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct BatteryState {
    pub header: Header,
    pub voltage: f32,
    pub temperature: f32,
    pub current: f32,
    pub charge: f32,
    pub capacity: f32,
    pub design_capacity: f32,
    pub percentage: f32,
    pub power_supply_status: u8,
    pub power_supply_health: u8,
    pub power_supply_technology: u8,
    pub present: bool,
    pub cell_voltage: Vec<f32>,
    pub cell_temperature: Vec<f32>,
    pub location: String,
    pub serial_number: String,
}
ros_message!(
    BatteryState,
    "sensor_msgs",
    "BatteryState",
    definition::BATTERY_STATE
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_heading_survives_the_quaternion() {
        for yaw in [-3.0, -1.2, 0.0, 0.5, 3.1] {
            assert!(
                (Quaternion::from_yaw(yaw).yaw() - yaw).abs() < 1e-12,
                "{yaw}"
            );
        }
        assert_eq!(Quaternion::default().w, 1.0);
    }

    #[test]
    fn times_split_into_seconds_and_nanoseconds() {
        let t = Time::from_secs(12.25);
        assert_eq!((t.sec, t.nanosec), (12, 250_000_000));
        assert!((t.as_secs() - 12.25).abs() < 1e-12);
        assert_eq!(Time::from_secs(f64::NAN), Time::default());
        assert_eq!(Time::from_secs(-4.0), Time::default());
        assert_eq!(Time::from_secs(1e300).sec, i32::MAX);
        // Rounding up to a whole second stays within the second.
        assert_eq!(Time::from_secs(1.999_999_999_9).nanosec, 999_999_999);
    }
}

/// `geometry_msgs/Transform`: where a child frame is in its parent.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Transform {
    pub translation: Vector3,
    pub rotation: Quaternion,
}

/// `geometry_msgs/TransformStamped`: `child_frame_id` in `header.frame_id`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct TransformStamped {
    pub header: Header,
    pub child_frame_id: String,
    pub transform: Transform,
}

/// `tf2_msgs/TFMessage`, on `tf` (and `tf_static`).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct TFMessage {
    pub transforms: Vec<TransformStamped>,
}
ros_message!(TFMessage, "tf2_msgs", "TFMessage", definition::TF_MESSAGE);

/// `rosgraph_msgs/Clock`, on `/clock`: simulated time for nodes with `use_sim_time`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Clock {
    pub clock: Time,
}
ros_message!(Clock, "rosgraph_msgs", "Clock", definition::CLOCK);
