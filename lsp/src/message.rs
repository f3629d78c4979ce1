//! Whether a message body is one tower-lsp-server can take (UTF-8 JSON that is a
//! JSON-RPC 2.0 request, notification or response), and the error answer when it is
//! not. Its decoder ends the session at the first body it cannot decode, so nothing
//! reaches it unchecked.

use serde_json::{Value, json};
use tower_lsp_server::jsonrpc::{Request, Response};

/// JSON-RPC 2.0: invalid JSON was received (also used for anything that could not be
/// read as a message at all: bad headers, bad UTF-8, an oversized message).
pub const PARSE_ERROR: i64 = -32700;
/// JSON-RPC 2.0: the JSON is not a valid request object.
pub const INVALID_REQUEST: i64 = -32600;

/// A message refused before the server saw it: the error object its sender gets.
#[derive(Debug, Clone, PartialEq)]
pub struct Rejection {
    pub code: i64,
    pub message: String,
    /// The request's id when it could be read, else null as JSON-RPC 2.0 prescribes.
    pub id: Value,
}

impl Rejection {
    pub fn new(code: i64, message: String) -> Rejection {
        Rejection {
            code,
            message,
            id: Value::Null,
        }
    }

    /// The error response, framed for the wire.
    pub fn response(&self) -> Vec<u8> {
        let title = match self.code {
            PARSE_ERROR => "Parse error",
            _ => "Invalid Request",
        };
        let body = json!({
            "jsonrpc": "2.0",
            "id": self.id,
            "error": {"code": self.code, "message": format!("{title}: {}", self.message)},
        })
        .to_string();
        format!("Content-Length: {}\r\n\r\n{body}", body.len()).into_bytes()
    }
}

/// Accepts exactly the bodies tower-lsp-server decodes: a request or notification,
/// else a response to one of the server's requests.
pub fn check(body: &[u8]) -> Result<(), Rejection> {
    let text = std::str::from_utf8(body).map_err(|e| {
        Rejection::new(
            PARSE_ERROR,
            format!("invalid UTF-8 at byte {} of the message", e.valid_up_to()),
        )
    })?;
    if serde_json::from_str::<Request>(text).is_ok()
        || serde_json::from_str::<Response>(text).is_ok()
    {
        return Ok(());
    }
    match serde_json::from_str::<Value>(text) {
        Err(e) => Err(Rejection::new(PARSE_ERROR, format!("invalid JSON: {e}"))),
        Ok(value) => {
            let id = match (value.get("method"), value.get("id")) {
                (Some(_), Some(id @ (Value::Number(_) | Value::String(_)))) => id.clone(),
                _ => Value::Null,
            };
            let what = if value.is_array() {
                "a batch; the Language Server Protocol has none"
            } else {
                "not a JSON-RPC 2.0 request, notification or response"
            };
            Err(Rejection {
                code: INVALID_REQUEST,
                message: what.to_string(),
                id,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refused(body: &[u8]) -> Rejection {
        check(body).expect_err("refused")
    }

    #[test]
    fn requests_notifications_and_responses_pass() {
        for body in [
            r#"{"jsonrpc":"2.0","id":1,"method":"shutdown"}"#,
            r#"{"jsonrpc":"2.0","method":"initialized","params":{}}"#,
            r#"{"jsonrpc":"2.0","id":"a","result":null}"#,
            r#"{"jsonrpc":"2.0","id":2,"error":{"code":-1,"message":"no"}}"#,
        ] {
            assert_eq!(check(body.as_bytes()), Ok(()), "{body}");
        }
    }

    #[test]
    fn bad_utf8_and_lone_surrogates_are_parse_errors() {
        let r = refused(b"{\"jsonrpc\":\"2.0\",\"method\":\"x\xff\"}");
        assert_eq!((r.code, r.id), (PARSE_ERROR, Value::Null));
        assert_eq!(r.message, "invalid UTF-8 at byte 28 of the message");
        let r = refused(br#"{"jsonrpc":"2.0","id":1,"method":"x","params":"\udcff"}"#);
        assert_eq!((r.code, r.id), (PARSE_ERROR, Value::Null));
        assert!(r.message.contains("surrogate"), "{}", r.message);
    }

    #[test]
    fn invalid_requests_keep_their_id() {
        let r = refused(br#"{"jsonrpc":"1.0","id":7,"method":"x"}"#);
        assert_eq!((r.code, r.id), (INVALID_REQUEST, json!(7)));
        let r = refused(br#"[{"jsonrpc":"2.0","id":1,"method":"x"}]"#);
        assert_eq!((r.code, r.id), (INVALID_REQUEST, Value::Null));
        assert!(r.message.contains("batch"));
    }

    #[test]
    fn deep_json_is_refused_without_recursing_deeply() {
        let body = format!("{}{}", "[".repeat(1_000_000), "]".repeat(1_000_000));
        assert_eq!(refused(body.as_bytes()).code, PARSE_ERROR);
    }

    #[test]
    fn the_response_is_framed() {
        let r = Rejection::new(PARSE_ERROR, "no Content-Length header".into());
        let text = String::from_utf8(r.response()).unwrap();
        let (head, body) = text.split_once("\r\n\r\n").unwrap();
        assert_eq!(head, format!("Content-Length: {}", body.len()));
        assert_eq!(
            serde_json::from_str::<Value>(body).unwrap(),
            json!({"jsonrpc": "2.0", "id": null,
                   "error": {"code": -32700, "message": "Parse error: no Content-Length header"}})
        );
    }
}
