//! Each message's definition in ROS 2's `.msg` language, with the definitions it uses
//! appended as rosbag2 writes them (a line of 80 `=`, then `MSG: pkg/Type`): the schema
//! an MCAP file's `ros2msg` channels carry, so that Foxglove and any rosbag2 reader
//! decode the recorded samples. Field for field as `msg.rs` (the upstream files'
//! comments and constants left out).

/// The `.msg` text of a type `concat!` can take (`concat!` wants literals).
macro_rules! msg {
    (Time) => {
        "int32 sec\nuint32 nanosec\n"
    };
    (Header) => {
        "builtin_interfaces/Time stamp\nstring frame_id\n"
    };
    (Vector3) => {
        "float64 x\nfloat64 y\nfloat64 z\n"
    };
    (Twist) => {
        "Vector3 linear\nVector3 angular\n"
    };
    (Point) => {
        "float64 x\nfloat64 y\nfloat64 z\n"
    };
    (Quaternion) => {
        "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n"
    };
    (Pose) => {
        "Point position\nQuaternion orientation\n"
    };
    (PoseWithCovariance) => {
        "Pose pose\nfloat64[36] covariance\n"
    };
    (TwistWithCovariance) => {
        "Twist twist\nfloat64[36] covariance\n"
    };
    (Transform) => {
        "Vector3 translation\nQuaternion rotation\n"
    };
    (TransformStamped) => {
        "std_msgs/Header header\nstring child_frame_id\nTransform transform\n"
    };
}

/// A dependency's block: the separator line, its name, its text.
macro_rules! uses {
    ($name:literal, $ty:ident) => {
        concat!(
            "================================================================================\nMSG: ",
            $name,
            "\n",
            msg!($ty)
        )
    };
}

pub const TWIST: &str = concat!(msg!(Twist), uses!("geometry_msgs/Vector3", Vector3));

pub const ODOMETRY: &str = concat!(
    "std_msgs/Header header\n",
    "string child_frame_id\n",
    "geometry_msgs/PoseWithCovariance pose\n",
    "geometry_msgs/TwistWithCovariance twist\n",
    uses!("std_msgs/Header", Header),
    uses!("builtin_interfaces/Time", Time),
    uses!("geometry_msgs/PoseWithCovariance", PoseWithCovariance),
    uses!("geometry_msgs/Pose", Pose),
    uses!("geometry_msgs/Point", Point),
    uses!("geometry_msgs/Quaternion", Quaternion),
    uses!("geometry_msgs/TwistWithCovariance", TwistWithCovariance),
    uses!("geometry_msgs/Twist", Twist),
    uses!("geometry_msgs/Vector3", Vector3),
);

pub const LASER_SCAN: &str = concat!(
    "std_msgs/Header header\n",
    "float32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\n",
    "float32 time_increment\nfloat32 scan_time\n",
    "float32 range_min\nfloat32 range_max\n",
    "float32[] ranges\nfloat32[] intensities\n",
    uses!("std_msgs/Header", Header),
    uses!("builtin_interfaces/Time", Time),
);

pub const BATTERY_STATE: &str = concat!(
    "std_msgs/Header header\n",
    "float32 voltage\nfloat32 temperature\nfloat32 current\nfloat32 charge\n",
    "float32 capacity\nfloat32 design_capacity\nfloat32 percentage\n",
    "uint8 power_supply_status\nuint8 power_supply_health\nuint8 power_supply_technology\n",
    "bool present\n",
    "float32[] cell_voltage\nfloat32[] cell_temperature\n",
    "string location\nstring serial_number\n",
    uses!("std_msgs/Header", Header),
    uses!("builtin_interfaces/Time", Time),
);

pub const TF_MESSAGE: &str = concat!(
    "geometry_msgs/TransformStamped[] transforms\n",
    uses!("geometry_msgs/TransformStamped", TransformStamped),
    uses!("std_msgs/Header", Header),
    uses!("builtin_interfaces/Time", Time),
    uses!("geometry_msgs/Transform", Transform),
    uses!("geometry_msgs/Vector3", Vector3),
    uses!("geometry_msgs/Quaternion", Quaternion),
);

pub const CLOCK: &str = concat!(
    "builtin_interfaces/Time clock\n",
    uses!("builtin_interfaces/Time", Time),
);

pub const HEADER: &str = concat!(msg!(Header), uses!("builtin_interfaces/Time", Time));
