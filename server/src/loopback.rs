//! A minimal HTTP/1.1 client for the server's own tools (`loadgen`,
//! `crashtest`) talking to a server on this machine: one request per
//! connection, the status and the body (a chunked body joined), with a
//! deadline so that a dead server cannot hang the tool.

use std::time::Duration;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;

/// How long one request may take.
const WITHIN: Duration = Duration::from_secs(30);

/// A request that got no answer.
#[derive(Debug, thiserror::Error)]
pub enum HttpError {
    #[error("{what}: {source}")]
    Io {
        what: String,
        source: std::io::Error,
    },
    #[error("{0}: no answer within 30 s")]
    Timeout(String),
    #[error("{0}: not an HTTP answer")]
    NotHttp(String),
}

/// One request with a JSON `body`; the status and the body of the answer.
pub async fn request(
    addr: &str,
    method: &str,
    path: &str,
    body: &str,
) -> Result<(u16, String), HttpError> {
    let what = || format!("{method} {path}");
    let exchange = async {
        let mut s = TcpStream::connect(addr).await?;
        let req = format!(
            "{method} {path} HTTP/1.1\r\nHost: {addr}\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}",
            body.len()
        );
        s.write_all(req.as_bytes()).await?;
        let mut raw = Vec::new();
        s.read_to_end(&mut raw).await?;
        Ok::<_, std::io::Error>(raw)
    };
    let raw = tokio::time::timeout(WITHIN, exchange)
        .await
        .map_err(|_| HttpError::Timeout(what()))?
        .map_err(|source| HttpError::Io {
            what: what(),
            source,
        })?;
    parse(&String::from_utf8_lossy(&raw)).ok_or_else(|| HttpError::NotHttp(what()))
}

/// The status and body of an HTTP/1.1 answer (a chunked body joined).
pub fn parse(text: &str) -> Option<(u16, String)> {
    let (head, rest) = text.split_once("\r\n\r\n")?;
    let status = head.split_whitespace().nth(1)?.parse().ok()?;
    let chunked = head
        .to_ascii_lowercase()
        .contains("transfer-encoding: chunked");
    let body = if chunked {
        dechunk(rest)?
    } else {
        rest.to_string()
    };
    Some((status, body))
}

fn dechunk(mut s: &str) -> Option<String> {
    let mut out = String::new();
    loop {
        let (size, rest) = s.split_once("\r\n")?;
        let n = usize::from_str_radix(size.trim(), 16).ok()?;
        if n == 0 {
            return Some(out);
        }
        out.push_str(rest.get(..n)?);
        s = rest.get(n + 2..)?;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn http_answers_parse_plain_and_chunked() {
        let plain = "HTTP/1.1 200 OK\r\ncontent-length: 2\r\n\r\n{}";
        assert_eq!(parse(plain), Some((200, "{}".into())));
        let chunked =
            "HTTP/1.1 201 Created\r\ntransfer-encoding: chunked\r\n\r\n3\r\n{\"a\r\n2\r\n\":\r\n0\r\n\r\n";
        assert_eq!(parse(chunked), Some((201, "{\"a\":".into())));
        assert_eq!(parse("garbage"), None);
        assert_eq!(
            parse("HTTP/1.1 200 OK\r\ntransfer-encoding: chunked\r\n\r\nzz\r\n"),
            None
        );
    }
}
