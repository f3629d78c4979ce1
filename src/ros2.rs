//! The options that connect `ilmrc` to a ROS 2 robot (`--robot ros2`), shared by the
//! commands that drive one, and the robot model's part in it: limits and the scanner
//! come from the model, as for a simulated robot.

use std::time::Duration;

use ilmr_model::RobotModel;
use ilmr_ros2::base::Frames;
use ilmr_ros2::convert::Limits;
use ilmr_ros2::dds::{MAX_DOMAIN_ID, Profile};
use ilmr_ros2::names::{TopicName, check_namespace};
use ilmr_ros2::{Reach, Ros2Config, Topics};

/// How long to wait for the robot's first odometry and scan, s, when not told.
const DEFAULT_WAIT: f64 = 10.0;

#[derive(clap::Args, Debug, Clone, Default)]
pub struct Ros2Args {
    /// With `--robot ros2`: the robot's namespace, such as `/robot1` (topics
    /// `/robot1/cmd_vel`, `/robot1/odom`, ...; default: the model's `[ROS2]
    /// namespace`, else `/`).
    #[arg(long)]
    pub ros_namespace: Option<String>,
    /// With `--robot ros2`: the DDS domain (default: the model's `[ROS2] domain`,
    /// else $ROS_DOMAIN_ID, else 0).
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

impl Ros2Args {
    /// Whether any option was given, for refusing them without `--robot ros2`.
    pub fn given(&self) -> Option<&'static str> {
        if self.ros_namespace.is_some() {
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

    /// Where the robot is and how to talk to it: each option, else the model's
    /// `[ROS2]` setting, else ROS 2's default. A setting the backend cannot use is an
    /// error that names the model and the setting.
    pub fn config(&self, model: &RobotModel) -> Result<Ros2Config, String> {
        let setting = |name: &str| model.ros2_value(name);
        let bad =
            |name: &str, why: String| format!("robot model `{}`, [ROS2] {name}: {why}", model.name);
        let namespace = match (&self.ros_namespace, setting("namespace")) {
            (Some(ns), _) => {
                check_namespace(ns).map_err(|e| format!("--ros-namespace: {e}"))?;
                ns.clone()
            }
            (None, Some(ns)) => {
                check_namespace(ns).map_err(|e| bad("namespace", e))?;
                ns.to_string()
            }
            (None, None) => "/".to_string(),
        };
        let domain_id = match (self.ros_domain, setting("domain")) {
            (Some(d), _) => d,
            (None, Some(d)) => d
                .parse::<u16>()
                .map_err(|_| bad("domain", format!("`{d}` is not a domain number")))?,
            (None, None) => domain_from_env(std::env::var("ROS_DOMAIN_ID").ok().as_deref())?,
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
        let defaults = Topics::default();
        let topic = |name: &str, default: String| -> Result<String, String> {
            let t = setting(name).map_or(default, str::to_string);
            TopicName::new(&namespace, &t).map_err(|e| bad(name, e))?;
            Ok(t)
        };
        let topics = Topics {
            cmd_vel: topic("cmd_vel", defaults.cmd_vel)?,
            odom: topic("odom", defaults.odom)?,
            scan: topic("scan", defaults.scan)?,
            battery: topic("battery_state", defaults.battery)?,
        };
        let sensor_profile = match setting("sensor_qos") {
            None | Some("best_effort") => Profile::SensorData,
            Some("reliable") => Profile::Reliable,
            Some(other) => {
                return Err(bad(
                    "sensor_qos",
                    format!("`{other}` is not `best_effort` or `reliable`"),
                ));
            }
        };
        let defaults = Frames::default();
        let frame = |name: &str, default: String| -> Result<String, String> {
            let f = setting(name).map_or(default, str::to_string);
            check_frame(&f).map_err(|e| bad(name, e))?;
            Ok(f)
        };
        let frames = Frames {
            world: defaults.world,
            odom: frame("odom_frame", defaults.odom)?,
            base: frame("base_frame", defaults.base)?,
            scanner: frame("scanner_frame", defaults.scanner)?,
        };
        let scanner = model
            .devices
            .iter()
            .find(|d| d.name.eq_ignore_ascii_case("scanner"))
            .map(|d| d.name.clone());
        Ok(Ros2Config {
            domain_id,
            namespace,
            topics,
            frames,
            sensor_profile,
            reach: if self.ros_loopback {
                Reach::Loopback
            } else {
                Reach::Network
            },
            scanner,
            limits: Limits::of(model),
            wait: Duration::from_secs_f64(wait),
            odometry_timeout: model.odometry_timeout(),
            scanner_timeout: model.scanner_timeout(),
        })
    }
}

/// A tf frame id: a word of letters, digits, `_`, `/` and `-`, as REP 105's are.
fn check_frame(frame: &str) -> Result<(), String> {
    let ok = !frame.is_empty()
        && frame.len() <= 64
        && frame
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || "_/-".contains(c));
    if ok {
        Ok(())
    } else {
        Err(format!(
            "`{}` is not a frame id (letters, digits, `_`, `/` and `-`)",
            frame.chars().take(64).collect::<String>()
        ))
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
            ros_namespace: Some("robot1".into()),
            ..Ros2Args::default()
        };
        assert!(bad.config(&moro).unwrap_err().contains("--ros-namespace"));
        let far = Ros2Args {
            ros_domain: Some(300),
            ..Ros2Args::default()
        };
        assert!(far.config(&moro).unwrap_err().contains("232"));
    }

    #[test]
    fn the_models_ros2_section_names_the_topics_and_options_override_it() {
        let (model, warnings) = RobotModel::parse(
            "[PARAMETERS]\nmax_speed 0.22\n[SENSORSANDACTUATORS]\nscanner 1 0 3500 360\n\
             [ROS2]\nnamespace /tb3\ndomain 30\ncmd_vel /cmd_vel_nav\nscan base_scan\n\
             sensor_qos reliable\nbase_frame base_footprint\n[END]\n",
            "tb3",
        );
        assert!(warnings.is_empty(), "{warnings:?}");
        let c = Ros2Args::default().config(&model).unwrap();
        assert_eq!((c.namespace.as_str(), c.domain_id), ("/tb3", 30));
        assert_eq!(c.topics.cmd_vel, "/cmd_vel_nav");
        assert_eq!(
            (c.topics.scan.as_str(), c.topics.odom.as_str()),
            ("base_scan", "odom")
        );
        assert_eq!(c.sensor_profile, Profile::Reliable);
        assert_eq!(c.frames.base, "base_footprint");
        let given = Ros2Args {
            ros_namespace: Some("/other".into()),
            ros_domain: Some(3),
            ..Ros2Args::default()
        };
        let c = given.config(&model).unwrap();
        assert_eq!((c.namespace.as_str(), c.domain_id), ("/other", 3));
        for (line, says) in [
            ("scan base scan", "2 fields"),
            ("scan 9scan", "[ROS2] scan"),
            ("sensor_qos fast", "[ROS2] sensor_qos"),
            ("domain 999", "above 232"),
            ("domain x", "[ROS2] domain"),
            ("base_frame a.b", "[ROS2] base_frame"),
        ] {
            let (m, w) = RobotModel::parse(&format!("[ROS2]\n{line}\n[END]\n"), "bad");
            let e = Ros2Args::default().config(&m).err();
            let said = e.or(w.first().map(|w| w.to_string())).unwrap_or_default();
            assert!(said.contains(says), "{line}: {said}");
        }
    }
}
