//! The tools' and tests' HTTP client (`tools/loopback.rs`) against a
//! one-answer server on loopback: what callers see of an answer.

#[path = "../tools/loopback.rs"]
mod loopback;

use std::io::{BufRead, BufReader, Write};
use std::net::TcpListener;

/// Serves one connection with `answer`; returns the address and the
/// request's head as it arrived.
fn answer_once(answer: &'static str) -> (String, std::thread::JoinHandle<String>) {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = listener.local_addr().unwrap().to_string();
    let served = std::thread::spawn(move || {
        let (stream, _) = listener.accept().unwrap();
        let mut reader = BufReader::new(stream.try_clone().unwrap());
        let mut head = String::new();
        loop {
            let mut line = String::new();
            reader.read_line(&mut line).unwrap();
            if line == "\r\n" || line.is_empty() {
                break;
            }
            head.push_str(&line);
        }
        (&stream).write_all(answer.as_bytes()).unwrap();
        head
    });
    (addr, served)
}

#[tokio::test]
async fn an_error_status_is_an_answer_and_a_chunked_body_is_joined() {
    let (addr, served) = answer_once(
        "HTTP/1.1 404 Not Found\r\ntransfer-encoding: chunked\r\n\r\n3\r\n{\"a\r\n2\r\n\":\r\n0\r\n\r\n",
    );
    let answer = loopback::request(&addr, "POST", "/x?y=1", &[("Origin", "http://o")], "{}")
        .await
        .unwrap();
    assert_eq!(answer, (404, "{\"a\":".to_string()));
    let head = served.join().unwrap().to_ascii_lowercase();
    assert!(head.starts_with("post /x?y=1 http/1.1\r\n"), "{head}");
    assert!(head.contains("origin: http://o\r\n"), "{head}");
    assert!(
        head.contains("content-type: application/json\r\n"),
        "{head}"
    );
}

#[tokio::test]
async fn no_server_is_a_transport_error_naming_the_request() {
    let addr = {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        listener.local_addr().unwrap().to_string()
    };
    let error = loopback::request(&addr, "GET", "/healthz", &[], "")
        .await
        .unwrap_err();
    assert!(matches!(error, loopback::HttpError::Transport { .. }));
    assert!(error.to_string().starts_with("GET /healthz: "), "{error}");
    assert!(std::error::Error::source(&error).is_some());
}
