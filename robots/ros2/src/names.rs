//! ROS 2 topic names and their DDS form, by ROS 2's "Topic and Service name mapping
//! to DDS" design: a name relative to a namespace (`cmd_vel` in `/robot1`) is
//! `/robot1/cmd_vel`, and DDS carries it as `rt/robot1/cmd_vel`.

use std::fmt;

/// DDS limits a topic name to 256 characters; ROS 2 keeps its own names shorter by
/// the `rt` prefix.
pub const MAX_NAME_CHARS: usize = 253;

/// A fully qualified ROS 2 topic name.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TopicName {
    /// `/robot1/cmd_vel`
    ros: String,
    /// `rt/robot1/cmd_vel`
    dds: String,
}

impl TopicName {
    /// `name` in `namespace`; an absolute `name` (`/cmd_vel`) ignores the namespace.
    pub fn new(namespace: &str, name: &str) -> Result<TopicName, String> {
        check_namespace(namespace)?;
        check_tokens(name, "topic name", name.starts_with('/'))?;
        let ros = if name.starts_with('/') {
            name.to_string()
        } else if namespace == "/" {
            format!("/{name}")
        } else {
            format!("{namespace}/{name}")
        };
        if ros.len() > MAX_NAME_CHARS {
            return Err(format!(
                "topic `{}...` is longer than the {MAX_NAME_CHARS} characters ROS 2 allows",
                ros.chars().take(40).collect::<String>()
            ));
        }
        let dds = format!("rt{ros}");
        Ok(TopicName { ros, dds })
    }

    pub fn ros(&self) -> &str {
        &self.ros
    }

    pub fn dds(&self) -> &str {
        &self.dds
    }
}

impl fmt::Display for TopicName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.ros)
    }
}

/// A namespace is `/` or an absolute name.
pub fn check_namespace(namespace: &str) -> Result<(), String> {
    if namespace == "/" {
        return Ok(());
    }
    if !namespace.starts_with('/') {
        return Err(format!(
            "namespace `{}` must start with `/` (as in `/robot1`)",
            shown(namespace)
        ));
    }
    check_tokens(namespace, "namespace", true)
}

fn check_tokens(name: &str, what: &str, absolute: bool) -> Result<(), String> {
    let body = if absolute { &name[1..] } else { name };
    if body.is_empty() {
        return Err(format!("the {what} `{}` is empty", shown(name)));
    }
    if body.ends_with('/') {
        return Err(format!("the {what} `{}` ends with `/`", shown(name)));
    }
    for token in body.split('/') {
        if token.is_empty() {
            return Err(format!("the {what} `{}` has `//` in it", shown(name)));
        }
        if token.starts_with(|c: char| c.is_ascii_digit()) {
            return Err(format!(
                "`{token}` in the {what} `{}` starts with a digit, which ROS 2 does not allow",
                shown(name)
            ));
        }
        if let Some(c) = token
            .chars()
            .find(|c| !(c.is_ascii_alphanumeric() || *c == '_'))
        {
            return Err(format!(
                "the {what} `{}` has `{}`: ROS 2 names take letters, digits, `_` and `/`",
                shown(name),
                c.escape_default()
            ));
        }
    }
    Ok(())
}

/// A name as an error message shows it: cut, so that a hostile argument does not fill
/// the terminal.
fn shown(name: &str) -> String {
    const SHOWN: usize = 60;
    if name.chars().count() > SHOWN {
        format!("{}...", name.chars().take(SHOWN).collect::<String>())
    } else {
        name.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_qualified_as_ros_2_does() {
        let n = TopicName::new("/robot1", "cmd_vel").unwrap();
        assert_eq!((n.ros(), n.dds()), ("/robot1/cmd_vel", "rt/robot1/cmd_vel"));
        let n = TopicName::new("/", "odom").unwrap();
        assert_eq!((n.ros(), n.dds()), ("/odom", "rt/odom"));
        let n = TopicName::new("/fleet/a", "/scan").unwrap();
        assert_eq!(n.dds(), "rt/scan", "an absolute name ignores the namespace");
        let n = TopicName::new("/a", "base/scan_front").unwrap();
        assert_eq!(n.dds(), "rt/a/base/scan_front");
    }

    #[test]
    fn bad_names_are_refused_with_the_reason() {
        for (ns, name, says) in [
            ("robot1", "cmd_vel", "must start with `/`"),
            ("/robot1/", "cmd_vel", "ends with `/`"),
            ("/a//b", "cmd_vel", "`//`"),
            ("/1robot", "cmd_vel", "starts with a digit"),
            ("/", "cmd vel", "has ` `"),
            ("/", "cmd-vel", "has `-`"),
            ("/", "", "is empty"),
            ("/", "/", "is empty"),
            ("/", "odom/", "ends with `/`"),
            ("/", "ödom", "has `\\u{f6}`"),
        ] {
            let e = TopicName::new(ns, name).unwrap_err();
            assert!(e.contains(says), "{ns} {name}: {e}");
        }
        let long = format!("/{}", "a".repeat(10_000));
        let e = TopicName::new(&long, "cmd_vel").unwrap_err();
        assert!(e.len() < 200, "{e}");
    }
}
