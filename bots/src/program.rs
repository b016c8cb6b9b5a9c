//! Any program as a [`Bot`]: it reads one [`DecideRequest`] per line on
//! its standard input and answers one decision per line on its standard
//! output (the JSON of `game::decide`: the same view in, the same
//! decision out as a hosted WebAssembly bot). A program that answers late,
//! answers nonsense or exits gives [`Decision::NoAnswer`], and the turn
//! runs out on the match's clock. Its standard error is passed through.

use crate::bot::{Bot, Context, Decision};
use game::decide::DecideRequest;
use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

/// Why a program could not be started.
#[derive(Debug, thiserror::Error)]
pub enum ProgramError {
    #[error("empty command")]
    Empty,
    #[error("could not start {command:?}: {source}")]
    Spawn {
        command: String,
        #[source]
        source: std::io::Error,
    },
}

/// A bot played by a child process.
pub struct ProgramBot {
    child: Child,
    stdin: Option<ChildStdin>,
    lines: mpsc::Receiver<String>,
    /// Why the last decision failed, if it did.
    pub last_error: Option<String>,
}

impl ProgramBot {
    /// Starts `command` (split on whitespace: the program and its
    /// arguments).
    pub fn spawn(command: &str) -> Result<ProgramBot, ProgramError> {
        let mut words = command.split_whitespace();
        let program = words.next().ok_or(ProgramError::Empty)?;
        let mut child = Command::new(program)
            .args(words)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .map_err(|source| ProgramError::Spawn {
                command: command.to_string(),
                source,
            })?;
        let stdin = child.stdin.take();
        let (tx, lines) = mpsc::channel();
        if let Some(out) = child.stdout.take() {
            // Lines are read on their own thread, so a silent program
            // cannot hold the match past a decision's deadline.
            std::thread::spawn(move || {
                for line in BufReader::new(out).lines() {
                    let Ok(line) = line else { break };
                    if tx.send(line).is_err() {
                        break;
                    }
                }
            });
        }
        Ok(ProgramBot {
            child,
            stdin,
            lines,
            last_error: None,
        })
    }

    fn ask(&mut self, request: &DecideRequest, wait: Duration) -> Result<Decision, String> {
        let stdin = self.stdin.as_mut().ok_or("the program's input is closed")?;
        writeln!(stdin, "{}", request.to_json())
            .and_then(|()| stdin.flush())
            .map_err(|e| format!("writing the request: {e}"))?;
        let line = self
            .lines
            .recv_timeout(wait)
            .map_err(|e| format!("no answer: {e}"))?;
        request
            .answer(line.trim().as_bytes())
            .map(Decision::from)
            .map_err(|e| e.to_string())
    }
}

impl Bot for ProgramBot {
    fn decide(&mut self, ctx: &Context) -> Decision {
        let request = DecideRequest {
            me: ctx.me,
            view: ctx.view.clone(),
        };
        match self.ask(&request, ctx.time_left()) {
            Ok(d) => {
                self.last_error = None;
                d
            }
            Err(e) => {
                self.last_error = Some(e);
                Decision::NoAnswer
            }
        }
    }
}

impl Drop for ProgramBot {
    fn drop(&mut self) {
        // Closing its input tells the program the match is over.
        self.stdin.take();
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
