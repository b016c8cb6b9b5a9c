//! The server's HTTP API from the test: one `GET` or `POST` over a fresh
//! connection, the answer parsed as JSON.

use crate::{E2eError, Result};
use std::time::Duration;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

/// `GET path` on `addr` (`host:port`); the status and the JSON body.
pub async fn get_json(addr: &str, path: &str) -> Result<(u16, serde_json::Value)> {
    request_json(addr, "GET", path, None).await
}

/// `POST path` with the JSON `body` on `addr`; the status and the JSON body.
pub async fn post_json(
    addr: &str,
    path: &str,
    body: &serde_json::Value,
) -> Result<(u16, serde_json::Value)> {
    request_json(addr, "POST", path, Some(&body.to_string())).await
}

async fn request_json(
    addr: &str,
    method: &str,
    path: &str,
    body: Option<&str>,
) -> Result<(u16, serde_json::Value)> {
    let io = |what: &str| {
        let what = format!("{method} {path}: {what}");
        move |source| E2eError::Io { what, source }
    };
    let mut stream = TcpStream::connect(addr).await.map_err(io("connect"))?;
    let content = match body {
        Some(b) => format!(
            "Content-Type: application/json\r\nContent-Length: {}\r\n\r\n{b}",
            b.len()
        ),
        None => "\r\n".to_string(),
    };
    let request =
        format!("{method} {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n{content}");
    stream
        .write_all(request.as_bytes())
        .await
        .map_err(io("send"))?;
    let mut raw = Vec::new();
    tokio::time::timeout(Duration::from_secs(10), stream.read_to_end(&mut raw))
        .await
        .map_err(|_| E2eError::Check(format!("{method} {path}: no answer within 10 s")))?
        .map_err(io("read"))?;
    let text = String::from_utf8_lossy(&raw);
    let bad = || E2eError::Check(format!("{method} {path}: malformed answer {text:?}"));
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
            "{method} {path}: chunked answers are not expected here"
        )));
    }
    let json = serde_json::from_str(body).map_err(|e| {
        E2eError::Check(format!(
            "{method} {path}: status {status}, not JSON ({e}): {body}"
        ))
    })?;
    Ok((status, json))
}
