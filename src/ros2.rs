//! The options that connect `ilmrc` to a ROS 2 robot (`--robot ros2`), shared by the
//! commands that drive one, and the robot model's part in it: limits and the scanner
//! come from the model, as for a simulated robot.

use std::time::Duration;

use ilmr_model::RobotModel;
use ilmr_ros2::convert::Limits;
use ilmr_ros2::dds::MAX_DOMAIN_ID;
use ilmr_ros2::{Reach, Ros2Config, Topics};

/// What `--robot` takes to drive a ROS 2 robot.
pub const ROBOT_NAME: &str = "ros2";

/// How long to wait for the robot's first odometry and scan, s, when not told.
const DEFAULT_WAIT: f64 = 10.0;

#[derive(clap::Args, Debug, Clone)]
pub struct Ros2Args {
    /// With `--robot ros2`: the robot's namespace, such as `/robot1` (topics
    /// `/robot1/cmd_vel`, `/robot1/odom`, ...).
    #[arg(long, default_value = "/")]
    pub ros_namespace: String,
    /// With `--robot ros2`: the DDS domain (default: $ROS_DOMAIN_ID, else 0).
    #[arg(long)]
    pub ros_domain: Option<u16>,
    /// With `--robot ros2`: seconds to wait for the robot's first odometry and scan.
    #[arg(long)]
    pub ros_wait: Option<f64>,
    /// With `--robot ros2`: keep DDS on the loopback interface (a robot on this
    /// computer, or tests).
    #[arg(long)]
    pub ros_loopback: bool,
}

impl Default for Ros2Args {
    fn default() -> Ros2Args {
        Ros2Args {
            ros_namespace: "/".into(),
            ros_domain: None,
            ros_wait: None,
            ros_loopback: false,
        }
    }
}

impl Ros2Args {
    /// Whether any option was given, for refusing them without `--robot ros2`.
    pub fn given(&self) -> Option<&'static str> {
        if self.ros_namespace != "/" {
            Some("--ros-namespace")
        } else if self.ros_domain.is_some() {
            Some("--ros-domain")
        } else if self.ros_wait.is_some() {
            Some("--ros-wait")
        } else if self.ros_loopback {
            Some("--ros-loopback")
        } else {
            None
        }
    }

    pub fn config(&self, model: &RobotModel) -> Result<Ros2Config, String> {
        ilmr_ros2::names::check_namespace(&self.ros_namespace)
            .map_err(|e| format!("--ros-namespace: {e}"))?;
        let domain_id = match self.ros_domain {
            Some(d) => d,
            None => domain_from_env(std::env::var("ROS_DOMAIN_ID").ok().as_deref())?,
        };
        if domain_id > MAX_DOMAIN_ID {
            return Err(format!(
                "DDS domain {domain_id} is above {MAX_DOMAIN_ID}, the largest ROS 2 uses"
            ));
        }
        let wait = self.ros_wait.unwrap_or(DEFAULT_WAIT);
        if !(wait.is_finite() && (0.0..=3600.0).contains(&wait)) {
            return Err(format!("--ros-wait {wait} is not a time of 0 to 3600 s"));
        }
        let scanner = model
            .devices
            .iter()
            .find(|d| d.name.eq_ignore_ascii_case("scanner"))
            .map(|d| d.name.clone());
        Ok(Ros2Config {
            domain_id,
            namespace: self.ros_namespace.clone(),
            topics: Topics::default(),
            reach: if self.ros_loopback {
                Reach::Loopback
            } else {
                Reach::Network
            },
            scanner,
            limits: Limits::of(model),
            wait: Duration::from_secs_f64(wait),
        })
    }
}

/// `ROS_DOMAIN_ID` as ROS 2 reads it: unset or empty is domain 0.
fn domain_from_env(value: Option<&str>) -> Result<u16, String> {
    match value.map(str::trim) {
        None | Some("") => Ok(0),
        Some(v) => v.parse::<u16>().map_err(|_| {
            format!(
                "ROS_DOMAIN_ID `{}` is not a domain number (0-{MAX_DOMAIN_ID})",
                v.chars().take(20).collect::<String>()
            )
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_domain_comes_from_the_environment_as_ros_2_reads_it() {
        assert_eq!(domain_from_env(None), Ok(0));
        assert_eq!(domain_from_env(Some("")), Ok(0));
        assert_eq!(domain_from_env(Some("42")), Ok(42));
        assert!(
            domain_from_env(Some("x"))
                .unwrap_err()
                .contains("ROS_DOMAIN_ID")
        );
    }

    #[test]
    fn the_config_takes_the_models_limits_and_scanner() {
        let moro = RobotModel::builtin("moro").unwrap();
        let c = Ros2Args {
            ros_domain: Some(7),
            ..Ros2Args::default()
        }
        .config(&moro)
        .unwrap();
        assert_eq!(c.domain_id, 7);
        assert_eq!(c.limits, Limits::of(&moro));
        assert_eq!(c.scanner.as_deref(), Some("scanner"));
        let bad = Ros2Args {
            ros_namespace: "robot1".into(),
            ..Ros2Args::default()
        };
        assert!(bad.config(&moro).unwrap_err().contains("--ros-namespace"));
        let far = Ros2Args {
            ros_domain: Some(300),
            ..Ros2Args::default()
        };
        assert!(far.config(&moro).unwrap_err().contains("232"));
    }
}
