//! The `[ROS2]` section: how a robot that speaks ROS 2 is reached, for
//! `--robot ros2` and `ilmrc sim --ros2` (docs/ros2.md). Values are words (a
//! topic, a frame, a profile) or a number (the domain); this crate keeps them as
//! text and knows their names, and the ROS 2 backend checks each value where it
//! uses it.

/// Every setting the section takes, with what it is.
pub const ROS2_SETTINGS: [(&str, &str); 10] = [
    (
        "namespace",
        "the robot's namespace, such as `/robot1` (`--ros-namespace` overrides it)",
    ),
    (
        "domain",
        "the DDS domain, 0-232 (`--ros-domain` overrides it; it overrides `ROS_DOMAIN_ID`)",
    ),
    ("cmd_vel", "the velocity command topic (default `cmd_vel`)"),
    ("odom", "the odometry topic (default `odom`)"),
    ("scan", "the laser scan topic (default `scan`)"),
    (
        "battery_state",
        "the battery topic (default `battery_state`)",
    ),
    (
        "odom_frame",
        "REP 105's odometry frame, which `ilmrc sim` publishes (default `odom`)",
    ),
    (
        "base_frame",
        "the robot's body frame, which `ilmrc sim` publishes (default `base_link`)",
    ),
    (
        "scanner_frame",
        "the scanner's frame, which `ilmrc sim` publishes (default `laser`)",
    ),
    (
        "sensor_qos",
        "`best_effort` (default; matches every publisher) or `reliable`: how odometry, scan and battery are read",
    ),
];

/// One `name value` line of `[ROS2]`.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Ros2Setting {
    pub name: String,
    pub value: String,
}

/// The setting the section's `name` is, if it is one.
pub fn ros2_setting(name: &str) -> Option<&'static str> {
    ROS2_SETTINGS
        .iter()
        .map(|(n, _)| *n)
        .find(|n| n.eq_ignore_ascii_case(name))
}

impl crate::RobotModel {
    /// The value of a `[ROS2]` setting, if the model gives it.
    pub fn ros2_value(&self, name: &str) -> Option<&str> {
        self.ros2
            .iter()
            .find(|s| s.name.eq_ignore_ascii_case(name))
            .map(|s| s.value.as_str())
    }
}

/// The `[ROS2]` settings as a Markdown table, for docs/robot-model.md.
pub fn ros2_table_markdown() -> String {
    let mut out = String::from("| setting | what |\n| --- | --- |\n");
    for (name, what) in ROS2_SETTINGS {
        out.push_str(&format!("| `{name}` | {what} |\n"));
    }
    out
}
