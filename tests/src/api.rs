//! Reading the server's HTTP API from the test: one `GET` over a fresh
//! connection, the answer parsed as JSON.

use crate::{E2eError, Result};
use std::time::Duration;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

/// `GET path` on `addr` (`host:port`); the status and the JSON body.
pub async fn get_json(addr: &str, path: &str) -> Result<(u16, serde_json::Value)> {
    let io = |what: &str| {
        let what = format!("GET {path}: {what}");
        move |source| E2eError::Io { what, source }
    };
    let mut stream = TcpStream::connect(addr).await.map_err(io("connect"))?;
    let request = format!("GET {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n");
    stream
        .write_all(request.as_bytes())
        .await
        .map_err(io("send"))?;
    let mut raw = Vec::new();
    tokio::time::timeout(Duration::from_secs(10), stream.read_to_end(&mut raw))
        .await
        .map_err(|_| E2eError::Check(format!("GET {path}: no answer within 10 s")))?
        .map_err(io("read"))?;
    let text = String::from_utf8_lossy(&raw);
    let bad = || E2eError::Check(format!("GET {path}: malformed answer {text:?}"));
    let (head, body) = text.split_once("\r\n\r\n").ok_or_else(bad)?;
    let status = head
        .split_whitespace()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .ok_or_else(bad)?;
    if head
        .to_ascii_lowercase()
        .contains("transfer-encoding: chunked")
    {
        return Err(E2eError::Check(format!(
            "GET {path}: chunked answers are not expected here"
        )));
    }
    let json = serde_json::from_str(body).map_err(|e| {
        E2eError::Check(format!(
            "GET {path}: status {status}, not JSON ({e}): {body}"
        ))
    })?;
    Ok((status, json))
}
