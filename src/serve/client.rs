//! Who a client is and what it may do: its token (the first request of a client
//! without a certificate), its role, the robot's lease for a driver's lines, and the
//! audit log's entries for what it did. The connection (`conn.rs`) asks here before
//! it hands a request to the robot.

use std::net::SocketAddr;
use std::sync::Arc;

use serde_json::{Map, Value};

use super::Server;
use super::access::Role;
use super::admit::Place;
use super::audit::Who;
use super::lease::{Driver, Grant, LEASE_TIME};
use super::outbox::Outbox;
use super::protocol::{self, LeaseAsk, Parsed, Request};

/// One connected client as the answering side sees it.
pub struct Client<'a> {
    pub conn: u64,
    pub place: &'a Place,
    pub server: &'a Server,
    pub outbox: &'a Arc<Outbox>,
    pub peer: Option<SocketAddr>,
}

impl Client<'_> {
    fn who(&self) -> Who<'_> {
        Who {
            identity: self.place.identity(),
            conn: self.conn,
            peer: self.peer,
        }
    }

    pub fn audit(&self, what: &str, fields: Map<String, Value>) {
        if let Some(audit) = &self.server.audit {
            audit.record(&self.who(), what, fields);
        }
    }
}

/// The first request of a client that came without a certificate: its token. The
/// answer, and whether the client is now known (else it is closed: a wrong token
/// gets no second try on the same connection).
pub fn authenticate(bytes: &[u8], client: &Client<'_>) -> (String, bool) {
    let refuse =
        |why: &str, id: Option<&Value>| (protocol::answer(protocol::error(why), id), false);
    let Some(access) = &client.server.access else {
        // A server that asks nobody knows every client from the start.
        return refuse("this server asks nobody who they are", None);
    };
    let Ok(text) = std::str::from_utf8(bytes) else {
        return refuse("not UTF-8; authenticate first: {\"auth\": TOKEN}", None);
    };
    let parsed = protocol::parse(text.trim());
    let Request::Auth(token) = &parsed.request else {
        return refuse(
            "authenticate first: send {\"auth\": TOKEN} (or connect with a client certificate)",
            parsed.id.as_ref(),
        );
    };
    let Some(identity) = access.by_token(token) else {
        client.audit("auth refused", Map::new());
        return refuse("unknown token", parsed.id.as_ref());
    };
    let mut answer = Map::new();
    answer.insert("ok".into(), Value::Bool(true));
    answer.insert("client".into(), Value::String(identity.name.clone()));
    answer.insert("role".into(), Value::String(identity.role.name().into()));
    let known = client.place.identify(identity).is_ok();
    client.audit("auth", Map::new());
    (protocol::answer(answer, parsed.id.as_ref()), known)
}

/// An audit entry's fields: the robot (on a fleet) and why, when there is a why.
pub fn robot_and_why(robot: &str, why: &str) -> Map<String, Value> {
    let mut m = Map::new();
    if !robot.is_empty() {
        m.insert("robot".into(), Value::String(robot.into()));
    }
    if !why.is_empty() {
        m.insert("why".into(), Value::String(why.into()));
    }
    m
}

/// Roles and leases apply where the server knows its clients (an access file).
fn roles_apply(client: &Client<'_>) -> bool {
    client.server.access.is_some()
}

/// Whether this client's role lets it `act` (lines, `cont`, a lease).
pub fn may_drive(client: &Client<'_>, act: &str) -> Result<(), String> {
    match client.place.identity() {
        Some(id) if id.role == Role::Observer && roles_apply(client) => Err(format!(
            "`{}` is an observer: only a driver may {act} (an observer may ask for status, \
             subscribe and stop)",
            id.name
        )),
        _ => Ok(()),
    }
}

/// A driver's line needs the robot's lease: taken if free, kept if held.
pub fn hold_lease(client: &Client<'_>, robot: &str) -> Result<(), String> {
    if !roles_apply(client) {
        return Ok(());
    }
    let driver = driver(client);
    match client.server.leases.take(robot, &driver)? {
        Grant::Renewed => {}
        Grant::Taken => client.audit("lease taken", lease_fields(robot, None)),
        Grant::TakenFrom(lapsed) => {
            client.audit("lease taken", lease_fields(robot, Some(&lapsed)));
        }
    }
    Ok(())
}

fn driver<'a>(client: &'a Client<'_>) -> Driver<'a> {
    Driver {
        conn: client.conn,
        client: client.place.identity().map_or("", |i| i.name.as_str()),
        outbox: client.outbox,
    }
}

fn lease_fields(robot: &str, from: Option<&str>) -> Map<String, Value> {
    let mut m = robot_and_why(robot, "");
    if let Some(from) = from {
        m.insert("from".into(), Value::String(from.into()));
    }
    m
}

/// `{"lease": "take" | "release" | "takeover"}`.
pub fn lease_answer(client: &Client<'_>, robot: &str, ask: LeaseAsk) -> Map<String, Value> {
    if !roles_apply(client) {
        return protocol::error(
            "this server has no access file: every client drives, and there is no lease",
        );
    }
    let leases = &client.server.leases;
    let driver = driver(client);
    let mut m = Map::new();
    match ask {
        LeaseAsk::Take => match leases.take(robot, &driver) {
            Err(why) => return protocol::error(&why),
            Ok(Grant::Renewed) => {}
            Ok(Grant::Taken) => client.audit("lease taken", lease_fields(robot, None)),
            Ok(Grant::TakenFrom(c)) => client.audit("lease taken", lease_fields(robot, Some(&c))),
        },
        LeaseAsk::Takeover => {
            let from = match leases.take_over(robot, &driver) {
                Grant::TakenFrom(c) => Some(c),
                Grant::Taken | Grant::Renewed => None,
            };
            client.audit("lease taken over", lease_fields(robot, from.as_deref()));
            if let Some(from) = from {
                m.insert("from".into(), Value::String(from));
            }
        }
        LeaseAsk::Release => {
            let gone = leases.release(client.conn, Some(robot));
            if gone.is_empty() {
                return protocol::error("this client does not hold the lease");
            }
            client.audit("lease released", robot_and_why(robot, ""));
            m.insert("ok".into(), Value::Bool(true));
            m.insert("lease".into(), Value::String("released".into()));
            return m;
        }
    }
    m.insert("ok".into(), Value::Bool(true));
    m.insert("lease".into(), Value::String("held".into()));
    m.insert("lapses_after".into(), Value::from(LEASE_TIME.as_secs()));
    m
}

/// What a status answer says of the asking client and of the robot's lease.
pub fn status_of_client(answer: &mut Map<String, Value>, client: &Client<'_>, robot: Option<&str>) {
    if let Some(id) = client.place.identity() {
        let mut you = Map::new();
        you.insert("client".into(), Value::String(id.name.clone()));
        you.insert("role".into(), Value::String(id.role.name().into()));
        answer.insert("you".into(), Value::Object(you));
    }
    if roles_apply(client) {
        let lease = match client.server.leases.holder(robot.unwrap_or("")) {
            None => Value::Null,
            Some((holder, left)) => {
                let mut l = Map::new();
                l.insert("holder".into(), Value::String(holder));
                l.insert(
                    "lapses_in".into(),
                    Value::from(left.as_millis() as f64 / 1000.0),
                );
                Value::Object(l)
            }
        };
        answer.insert("lease".into(), lease);
    }
}

/// Lines, `cont` and `stop` go into the audit log with their outcome.
pub fn audit_answer(client: &Client<'_>, parsed: &Parsed, answer: &Map<String, Value>) {
    let what = match &parsed.request {
        Request::Ilmr(text) if text == "cont" => "cont",
        Request::Ilmr(_) => "line",
        Request::Stop => "stop",
        _ => return,
    };
    let mut fields = robot_and_why(parsed.robot.as_deref().unwrap_or(""), "");
    if let Request::Ilmr(text) = &parsed.request {
        fields.insert("text".into(), Value::String(text.clone()));
    }
    for key in ["ok", "t", "error"] {
        if let Some(v) = answer.get(key) {
            fields.insert(key.into(), v.clone());
        }
    }
    if let Some(Value::Array(d)) = answer.get("diagnostics") {
        fields.insert("diagnostics".into(), Value::from(d.len()));
    }
    client.audit(what, fields);
}
