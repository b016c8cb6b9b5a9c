//! One game between two bots on a running server, as two clients of it:
//! the first creates the match with the tournament's rules, the second
//! joins it, and both play it out through the [`Runner`] (HTTP and
//! WebSocket, reconnecting if the connection drops). The server draws the
//! seed, so such a game is real but not repeatable; its record stays on
//! the server, listed with the finished matches and replayable in the web
//! client.

use crate::arena::MatchReport;
use crate::bot::Bot;
use crate::runner::{CreateMatch, Runner, RunnerError};
use game::{Config, RecordedMove};

/// Plays `first` (the creator's seat) against `second` on `server` under
/// `config`; `names` are the seats' names on the server.
pub fn play_on_server(
    server: &str,
    config: &Config,
    first: Box<dyn Bot>,
    second: Box<dyn Bot>,
    names: [&str; 2],
) -> Result<MatchReport, RunnerError> {
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .map_err(|source| RunnerError::Read {
            what: "starting the client's runtime".into(),
            source,
        })?;
    rt.block_on(async {
        let runner = Runner::new(server)?;
        let create = CreateMatch {
            name: Some(names[0].to_string()),
            ..CreateMatch::open(config.clone())
        };
        let a = runner.create(&create).await?;
        let b = runner.join(&a.match_id, Some(names[1])).await?;
        let (ra, rb) = tokio::join!(runner.play(&a, first), runner.play(&b, second));
        let ((ra, _), (rb, _)) = (ra?, rb?);
        let record = match ra.record.clone() {
            Some(r) => r,
            None => runner.record(&a.match_id).await?,
        };
        let swapped = record
            .moves
            .iter()
            .any(|m| matches!(m, RecordedMove::Pie { swap: true }));
        let timeouts = record
            .moves
            .iter()
            .filter(|m| matches!(m, RecordedMove::Pass { .. }))
            .count() as u32;
        Ok(MatchReport {
            result: ra.result.or(rb.result),
            shots: ra.shots.max(rb.shots),
            swapped,
            refusals: (ra.errors.len() + rb.errors.len()) as u32,
            timeouts,
            record,
        })
    })
}
