//! One driver at a time: a robot's lease. A driver takes it with its first line (or
//! `{"lease": "take"}`) when nobody holds it, renews it with every request, and gives
//! it up by `release`, by leaving, or by falling silent for `LEASE_TIME`. Another
//! driver takes it only by `{"lease": "takeover"}`, and the one it was taken from is
//! told at once.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, MutexGuard, Weak};
use std::time::{Duration, Instant};

use serde_json::{Map, Value, json};

use super::outbox::Outbox;
use crate::live::engine::EventSink;

/// A lease its holder has not renewed for this long is free for the next driver.
pub const LEASE_TIME: Duration = Duration::from_secs(30);

struct Holder {
    conn: u64,
    client: String,
    renewed: Instant,
    /// Where to tell the holder it lost the lease.
    outbox: Weak<Outbox>,
}

/// Every robot's lease, by robot name (`""` for a server of one robot).
#[derive(Default)]
pub struct Leases {
    held: Mutex<HashMap<String, Holder>>,
}

/// A driver, as the leases see it.
pub struct Driver<'a> {
    pub conn: u64,
    pub client: &'a str,
    pub outbox: &'a Arc<Outbox>,
}

/// What asking for a lease came to.
#[derive(Debug, PartialEq, Eq)]
pub enum Grant {
    /// The driver held it already.
    Renewed,
    /// It was free; the driver holds it now.
    Taken,
    /// It was taken from this client.
    TakenFrom(String),
}

impl Leases {
    fn held(&self) -> MutexGuard<'_, HashMap<String, Holder>> {
        self.held
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// The lease of `robot` for this driver: renewed if it holds it, taken if it is
    /// free or lapsed; else why not.
    pub fn take(&self, robot: &str, driver: &Driver<'_>) -> Result<Grant, String> {
        let mut held = self.held();
        let now = Instant::now();
        if let Some(h) = held.get(robot)
            && h.conn != driver.conn
            && now.duration_since(h.renewed) < LEASE_TIME
        {
            let left = LEASE_TIME.saturating_sub(now.duration_since(h.renewed));
            return Err(format!(
                "{} is driven by `{}` (connection {}; its lease lapses {} s after its last \
                 request, in {} s at most): send {{\"lease\": \"takeover\"}} to take it over",
                robot_name(robot),
                h.client,
                h.conn,
                LEASE_TIME.as_secs(),
                left.as_secs().max(1)
            ));
        }
        match held.insert(robot.to_string(), holder(driver, now)) {
            Some(lapsed) if lapsed.conn != driver.conn => {
                tell(&lapsed, robot, "lapsed", driver.client);
                Ok(Grant::TakenFrom(lapsed.client))
            }
            Some(_) => Ok(Grant::Renewed),
            None => Ok(Grant::Taken),
        }
    }

    /// Takes the lease whoever holds it; the holder is sent a `lease` event.
    pub fn take_over(&self, robot: &str, driver: &Driver<'_>) -> Grant {
        let mut held = self.held();
        let before = held.insert(robot.to_string(), holder(driver, Instant::now()));
        match before {
            Some(h) if h.conn != driver.conn => {
                tell(&h, robot, "taken over", driver.client);
                Grant::TakenFrom(h.client)
            }
            Some(_) => Grant::Renewed,
            None => Grant::Taken,
        }
    }

    /// Renews the lease if this connection holds it (any request it makes).
    pub fn renew(&self, conn: u64) {
        let now = Instant::now();
        for h in self.held().values_mut().filter(|h| h.conn == conn) {
            h.renewed = now;
        }
    }

    /// Gives up what this connection holds (on `release`, or as it leaves): the
    /// robots it held.
    pub fn release(&self, conn: u64, robot: Option<&str>) -> Vec<String> {
        let mut held = self.held();
        let gone: Vec<String> = held
            .iter()
            .filter(|(r, h)| h.conn == conn && robot.is_none_or(|want| want == r.as_str()))
            .map(|(r, _)| r.clone())
            .collect();
        for r in &gone {
            held.remove(r);
        }
        gone
    }

    /// Who holds `robot`'s lease, and for how much longer without a request.
    pub fn holder(&self, robot: &str) -> Option<(String, Duration)> {
        let held = self.held();
        let h = held.get(robot)?;
        let since = h.renewed.elapsed();
        (since < LEASE_TIME).then(|| (h.client.clone(), LEASE_TIME - since))
    }
}

fn holder(driver: &Driver<'_>, now: Instant) -> Holder {
    Holder {
        conn: driver.conn,
        client: driver.client.to_string(),
        renewed: now,
        outbox: Arc::downgrade(driver.outbox),
    }
}

/// A `lease` event to the driver that lost `robot`'s lease: how, and to whom.
fn tell(lost: &Holder, robot: &str, how: &str, by: &str) {
    let Some(out) = lost.outbox.upgrade() else {
        return;
    };
    let mut event = Map::new();
    event.insert("event".into(), json!("lease"));
    if !robot.is_empty() {
        event.insert("robot".into(), json!(robot));
    }
    event.insert("lease".into(), json!(how));
    event.insert("by".into(), json!(by));
    out.offer(&Arc::from(Value::Object(event).to_string()));
}

fn robot_name(robot: &str) -> String {
    if robot.is_empty() {
        "the robot".into()
    } else {
        format!("robot `{robot}`")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_driver_holds_a_robot_and_a_takeover_tells_the_one_before() {
        let leases = Leases::default();
        let (a, b) = (Arc::new(Outbox::default()), Arc::new(Outbox::default()));
        let planner = Driver {
            conn: 1,
            client: "planner",
            outbox: &a,
        };
        let laptop = Driver {
            conn: 2,
            client: "laptop",
            outbox: &b,
        };
        assert_eq!(leases.take("", &planner), Ok(Grant::Taken));
        assert_eq!(
            leases.take("", &planner),
            Ok(Grant::Renewed),
            "a holder renews"
        );
        let refused = leases.take("", &laptop).expect_err("held by the planner");
        assert!(
            refused.contains("`planner`") && refused.contains("takeover"),
            "{refused}"
        );
        // Another robot of a fleet is free.
        assert_eq!(leases.take("r2", &laptop), Ok(Grant::Taken));
        assert_eq!(
            leases.take_over("", &laptop),
            Grant::TakenFrom("planner".into())
        );
        let told = a.take().unwrap_or_default();
        assert_eq!(told.len(), 1);
        let event: Value = serde_json::from_str(&told[0].0).expect("JSON");
        assert_eq!(
            event,
            json!({"event": "lease", "lease": "taken over", "by": "laptop"})
        );
        assert!(leases.take("", &planner).is_err(), "the planner lost it");
        assert_eq!(leases.holder("").map(|h| h.0), Some("laptop".into()));
        let mut gone = leases.release(2, None);
        gone.sort();
        assert_eq!(gone, ["", "r2"]);
        assert_eq!(leases.take("", &planner), Ok(Grant::Taken), "free again");
    }
}
