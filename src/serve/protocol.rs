//! The wire format: one JSON object per line each way (docs/serve.md). Parsing a
//! request never fails the connection; what cannot be understood becomes
//! [`Request::Invalid`], answered with an error object.

use serde_json::{Map, Value, json};

/// What a client asked for.
#[derive(Debug, Clone, PartialEq)]
pub enum Request {
    /// ILMR text to join the running task: one line or a block.
    Ilmr(String),
    Status,
    /// The emergency stop: the line `stop`, on its own path (`live::stop`).
    Stop,
    /// Start sending the trace's events on this connection.
    Subscribe,
    /// A client's token: the first request to a server with an access file, unless
    /// the client came with a certificate.
    Auth(String),
    /// A driver asks for the robot's lease, gives it up, or takes it from another.
    Lease(LeaseAsk),
    /// Not a request: why, for the error object.
    Invalid(String),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LeaseAsk {
    Take,
    Release,
    Takeover,
}

/// A request line, the `id` the client gave it (echoed in the answer) and the robot
/// it is for (`"robot"`, on a server of a fleet).
#[derive(Debug, Clone, PartialEq)]
pub struct Parsed {
    pub request: Request,
    pub id: Option<Value>,
    pub robot: Option<String>,
}

pub fn parse(line: &str) -> Parsed {
    let value: Value = match serde_json::from_str(line) {
        Ok(v) => v,
        Err(e) => {
            return Parsed {
                request: Request::Invalid(format!("not JSON: {e}")),
                id: None,
                robot: None,
            };
        }
    };
    let Value::Object(mut object) = value else {
        return Parsed {
            request: Request::Invalid("expected a JSON object".into()),
            id: None,
            robot: None,
        };
    };
    let id = object.remove("id");
    let (robot, request) = match object.remove("robot") {
        None => (None, request_of(&object)),
        Some(Value::String(name)) => (Some(name), request_of(&object)),
        Some(_) => (
            None,
            Request::Invalid("\"robot\" takes a robot's name, a string".into()),
        ),
    };
    Parsed { request, id, robot }
}

fn request_of(object: &Map<String, Value>) -> Request {
    let keys: Vec<&str> = object.keys().map(String::as_str).collect();
    let [key] = keys[..] else {
        return Request::Invalid(format!(
            "expected exactly one of \"ilmr\", \"status\", \"stop\", \"cont\", \"subscribe\", \
             \"auth\", \"lease\" (besides \"id\" and \"robot\"), got {}",
            if keys.is_empty() {
                "none".to_string()
            } else {
                keys.join(", ")
            }
        ));
    };
    let value = &object[key];
    match (key, value) {
        ("ilmr", Value::String(text)) => Request::Ilmr(text.clone()),
        ("ilmr", _) => Request::Invalid("\"ilmr\" takes a string of ILMR text".into()),
        ("status", Value::Bool(true)) => Request::Status,
        // `stop` and `cont` are the language's own commands; joining them as lines
        // gives them the same meaning and the same trace as typing them. `stop` takes
        // the emergency path to the robot, around the lines being compiled.
        ("stop", Value::Bool(true)) => Request::Stop,
        ("cont", Value::Bool(true)) => Request::Ilmr("cont".into()),
        ("subscribe", Value::String(s)) if s == "events" => Request::Subscribe,
        ("subscribe", _) => Request::Invalid("\"subscribe\" takes \"events\"".into()),
        ("auth", Value::String(token)) => Request::Auth(token.clone()),
        ("auth", _) => Request::Invalid("\"auth\" takes the client's token, a string".into()),
        ("lease", Value::String(s)) if s == "take" => Request::Lease(LeaseAsk::Take),
        ("lease", Value::String(s)) if s == "release" => Request::Lease(LeaseAsk::Release),
        ("lease", Value::String(s)) if s == "takeover" => Request::Lease(LeaseAsk::Takeover),
        ("lease", _) => {
            Request::Invalid("\"lease\" takes \"take\", \"release\" or \"takeover\"".into())
        }
        ("status" | "stop" | "cont", _) => Request::Invalid(format!("\"{key}\" takes true")),
        _ => Request::Invalid(format!("unknown request \"{key}\"")),
    }
}

/// An answer object as one line, with the request's `id` when it had one.
pub fn answer(mut body: Map<String, Value>, id: Option<&Value>) -> String {
    if let Some(id) = id {
        body.insert("id".into(), id.clone());
    }
    Value::Object(body).to_string()
}

/// `{"ok": false, "error": message}`.
pub fn error(message: &str) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("ok".into(), json!(false));
    m.insert("error".into(), json!(message));
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_parse_and_shorthands_become_lines() {
        assert_eq!(
            parse(r#"{"ilmr": "goahead(1)"}"#).request,
            Request::Ilmr("goahead(1)".into())
        );
        assert_eq!(parse(r#"{"stop": true}"#).request, Request::Stop);
        assert_eq!(
            parse(r#"{"cont": true, "id": 7}"#),
            Parsed {
                request: Request::Ilmr("cont".into()),
                id: Some(json!(7)),
                robot: None,
            }
        );
        assert_eq!(parse(r#"{"status": true}"#).request, Request::Status);
        assert_eq!(
            parse(r#"{"subscribe": "events"}"#).request,
            Request::Subscribe
        );
        assert_eq!(
            parse(r#"{"auth": "abc"}"#).request,
            Request::Auth("abc".into())
        );
        assert_eq!(
            parse(r#"{"lease": "takeover"}"#).request,
            Request::Lease(LeaseAsk::Takeover)
        );
        let to_r2 = parse(r#"{"robot": "r2", "ilmr": "goahead(1)"}"#);
        assert_eq!(to_r2.robot.as_deref(), Some("r2"));
        assert_eq!(to_r2.request, Request::Ilmr("goahead(1)".into()));
    }

    #[test]
    fn what_is_not_a_request_says_why() {
        let invalid = |line: &str| match parse(line).request {
            Request::Invalid(why) => why,
            other => panic!("{line} parsed as {other:?}"),
        };
        assert!(invalid("{\"ilmr\": ").starts_with("not JSON"));
        assert!(invalid("[1]").contains("object"));
        assert!(invalid("{}").contains("none"));
        assert!(invalid(r#"{"ilmr": "a", "status": true}"#).contains("exactly one"));
        assert!(invalid(r#"{"ilmr": 3}"#).contains("string"));
        assert!(invalid(r#"{"status": false}"#).contains("true"));
        assert!(invalid(r#"{"subscribe": "poses"}"#).contains("events"));
        assert!(invalid(r#"{"auth": 1}"#).contains("token"));
        assert!(invalid(r#"{"lease": "steal"}"#).contains("takeover"));
        assert!(invalid(r#"{"fly": true}"#).contains("unknown request \"fly\""));
        assert!(invalid(r#"{"robot": 3, "status": true}"#).contains("robot's name"));
    }

    #[test]
    fn answers_carry_the_id() {
        let line = answer(error("bad"), Some(&json!("a")));
        let back: Value = serde_json::from_str(&line).expect("an answer is JSON");
        assert_eq!(back, json!({"ok": false, "error": "bad", "id": "a"}));
        assert!(!line.contains('\n'));
    }
}
