//! One JSON request to a server over HTTP (`ureq`), and what can go wrong with it, said in
//! words that name the server.
//!
//! Invariant: every failure is a [`ServerError`] that names the server and says whether
//! trying again later may help (unreachable, timed out, a 5xx or 429 answer) or not
//! (any other HTTP error, an answer that is not what the protocol says).

use std::time::Duration;

/// Largest answer read from a server (a batch of 512² PNGs in base64 is a few MB).
const MAX_ANSWER: u64 = 256 << 20;

/// A request to a server that failed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{server}: {what}")]
pub struct ServerError {
    /// The server's URL, as the user gave it.
    pub server: String,
    pub what: String,
    /// Trying again later may help.
    pub transient: bool,
}

impl ServerError {
    pub fn new(server: &str, what: impl Into<String>, transient: bool) -> ServerError {
        ServerError {
            server: server.to_string(),
            what: what.into(),
            transient,
        }
    }
}

/// An HTTP client that waits at most `timeout` for one whole exchange.
pub fn agent(timeout: Duration) -> ureq::Agent {
    ureq::Agent::config_builder()
        .timeout_global(Some(timeout))
        .http_status_as_error(false)
        .build()
        .into()
}

/// `base` and `path` joined with one slash between them.
pub fn join(base: &str, path: &str) -> String {
    format!(
        "{}/{}",
        base.trim_end_matches('/'),
        path.trim_start_matches('/')
    )
}

/// POSTs `body` (JSON) to `url` and returns the answer's JSON; `server` is what errors name.
pub fn post_json(
    agent: &ureq::Agent,
    server: &str,
    url: &str,
    body: &serde_json::Value,
    bearer: Option<&str>,
) -> Result<serde_json::Value, ServerError> {
    let mut request = agent.post(url).header("Content-Type", "application/json");
    if let Some(key) = bearer {
        request = request.header("Authorization", &format!("Bearer {key}"));
    }
    let mut response = request
        .send(body.to_string())
        .map_err(|e| transport(server, url, &e))?;
    let status = response.status().as_u16();
    let text = response
        .body_mut()
        .with_config()
        .limit(MAX_ANSWER)
        .read_to_string()
        .map_err(|e| transport(server, url, &e))?;
    if !(200..300).contains(&status) {
        let transient = status >= 500 || status == 429;
        let what = format!("{url} answered HTTP {status}{}", excerpt(&text));
        return Err(ServerError::new(server, what, transient));
    }
    serde_json::from_str(&text).map_err(|e| {
        let what = format!("{url} answered with malformed JSON ({e}){}", excerpt(&text));
        ServerError::new(server, what, false)
    })
}

/// The start of an answer's text, to show with an error (empty when there is none).
fn excerpt(text: &str) -> String {
    let t = text.trim();
    if t.is_empty() {
        return String::new();
    }
    let cut: String = t.chars().take(120).collect();
    let more = if cut.len() < t.len() { "…" } else { "" };
    format!(": `{cut}{more}`")
}

/// Whether an I/O error says nobody answers at the address.
fn unreachable(kind: std::io::ErrorKind) -> bool {
    use std::io::ErrorKind::*;
    matches!(
        kind,
        ConnectionRefused | ConnectionReset | ConnectionAborted | NotConnected | AddrNotAvailable
    )
}

/// A failure to reach `url` or to read its answer.
fn transport(server: &str, url: &str, e: &ureq::Error) -> ServerError {
    let what = match e {
        ureq::Error::Timeout(_) => format!("{url} did not answer in time (--timeout)"),
        ureq::Error::ConnectionFailed | ureq::Error::HostNotFound => {
            format!("cannot reach {url} ({e})")
        }
        ureq::Error::Io(io) if unreachable(io.kind()) => format!("cannot reach {url} ({io})"),
        ureq::Error::BodyExceedsLimit(n) => format!("{url} answered more than {n} bytes"),
        _ => format!("{url}: {e}"),
    };
    let transient = !matches!(
        e,
        ureq::Error::BadUri(_) | ureq::Error::BodyExceedsLimit(_) | ureq::Error::Http(_)
    );
    ServerError::new(server, what, transient)
}
