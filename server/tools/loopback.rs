//! The HTTP client of the server's own tools (`loadgen`, `crashtest`) and
//! of its end-to-end tests, talking to a server on this machine: `ureq`
//! (blocking) run on tokio's blocking threads, so that no async worker
//! waits on the network; one request per connection (no pool: a server
//! the tests restart on a port gets no stale connection), every status a
//! value (4xx and 5xx answers are what the callers check), the body as
//! text, and a deadline so that a dead server cannot hang a tool.
//!
//! Not a module of the server library, whose users never make HTTP
//! requests: the binaries and the tests each include this one file
//! (`#[path]`), so it must not import anything of theirs.

use std::io::Read as _;
use std::time::Duration;

/// How long one request may take, the answer's body read included.
pub const WITHIN: Duration = Duration::from_secs(30);

/// A request that got no answer.
#[derive(Debug, thiserror::Error)]
pub enum HttpError {
    /// No connection, no HTTP answer or none in time.
    #[error("{what}: {source}")]
    Transport {
        what: String,
        source: Box<ureq::Transport>,
    },
    /// The answer's body could not be read.
    #[error("{what}: reading the answer: {source}")]
    Body {
        what: String,
        source: std::io::Error,
    },
    /// The blocking thread that made the request panicked or was cancelled.
    #[error("{what}: {source}")]
    Join {
        what: String,
        source: tokio::task::JoinError,
    },
}

/// One request to `addr` (`host:port`) with a JSON `body` and extra
/// `headers`; the status and the body of the answer, whatever the status.
pub async fn request(
    addr: &str,
    method: &str,
    path: &str,
    headers: &[(&str, &str)],
    body: &str,
) -> Result<(u16, String), HttpError> {
    let what = format!("{method} {path}");
    let url = format!("http://{addr}{path}");
    let (method, body) = (method.to_string(), body.to_string());
    let headers: Vec<(String, String)> = headers
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect();
    let exchange = {
        let what = what.clone();
        move || blocking(&what, &method, &url, &headers, &body)
    };
    tokio::task::spawn_blocking(exchange)
        .await
        .map_err(|source| HttpError::Join { what, source })?
}

/// The request itself, on the calling thread.
fn blocking(
    what: &str,
    method: &str,
    url: &str,
    headers: &[(String, String)],
    body: &str,
) -> Result<(u16, String), HttpError> {
    let agent = ureq::AgentBuilder::new()
        .timeout(WITHIN)
        .max_idle_connections(0)
        .build();
    let mut req = agent.request(method, url);
    for (name, value) in headers {
        req = req.set(name, value);
    }
    let answer = match req
        .set("Content-Type", "application/json")
        .send_string(body)
    {
        Ok(answer) => answer,
        // ureq 2 returns 4xx and 5xx answers as errors: here they are answers.
        Err(ureq::Error::Status(_, answer)) => answer,
        Err(ureq::Error::Transport(source)) => {
            return Err(HttpError::Transport {
                what: what.to_string(),
                source: Box::new(source),
            })
        }
    };
    let status = answer.status();
    let mut raw = Vec::new();
    answer
        .into_reader()
        .read_to_end(&mut raw)
        .map_err(|source| HttpError::Body {
            what: what.to_string(),
            source,
        })?;
    Ok((status, String::from_utf8_lossy(&raw).into_owned()))
}
