//! The comparison both binding tests make (JavaScript in Node, Python):
//! the same simulation requests run through the binding and natively
//! through `SimulateRequest::run`, each answer read back into the game's
//! own types and written by serde_json (the shortest text that reads back
//! to the same bits, so equal text is equal bits), error answers reduced
//! to their code; the first request that differs is named.

use game::{SimulateRequest, Simulation};

/// What native Rust answers for `req`, in the form answers are compared.
pub fn native_line(req: &SimulateRequest) -> String {
    match req.run() {
        Ok(sim) => serde_json::to_string(&sim).unwrap_or_default(),
        Err(e) => serde_json::json!({ "error": e.code().as_str() }).to_string(),
    }
}

/// A binding's answer line in the native form: a Simulation re-serialised
/// (so only the numbers' bits can differ, never their spelling), or the
/// error code alone.
pub fn normalise(line: &str) -> Result<String, String> {
    let v: serde_json::Value =
        serde_json::from_str(line).map_err(|e| format!("not JSON ({e}): {line}"))?;
    if let Some(code) = v.get("error") {
        return Ok(serde_json::json!({ "error": code }).to_string());
    }
    let sim: Simulation =
        serde_json::from_str(line).map_err(|e| format!("not a Simulation ({e}): {line}"))?;
    serde_json::to_string(&sim).map_err(|e| e.to_string())
}

/// What the native side did over all the requests compared.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    /// Requests refused (with an error code).
    pub errors: usize,
    /// Pieces knocked off, over all the shots.
    pub knocked: usize,
}

/// Checks that `answers` (one line per request, from the binding `who`)
/// carry the very bits native Rust gives for `requests` (drawn from
/// `seed`); the native tally, or which requests differ and how the first
/// one does.
pub fn check(
    who: &str,
    seed: u64,
    requests: &[SimulateRequest],
    answers: &[String],
) -> Result<Tally, String> {
    if answers.len() != requests.len() {
        return Err(format!(
            "{who} answered {} lines for {} requests",
            answers.len(),
            requests.len()
        ));
    }
    let mut tally = Tally::default();
    let mut differ = Vec::new();
    let mut first = None;
    for (k, (req, answer)) in requests.iter().zip(answers).enumerate() {
        match req.run() {
            Ok(sim) => tally.knocked += sim.knocked_off.len(),
            Err(_) => tally.errors += 1,
        }
        let want = native_line(req);
        let got = normalise(answer).map_err(|e| format!("{who}, request {k}: {e}"))?;
        if got != want {
            differ.push(k);
            first.get_or_insert((k, want, got));
        }
    }
    match first {
        None => Ok(tally),
        Some((k, want, got)) => Err(format!(
            "{} of {} requests differ; the first, request {k} (seed {seed:#x}, {k} requests \
             in):\n  request: {}\n  native:  {want}\n  {who}: {got}",
            differ.len(),
            requests.len(),
            serde_json::to_string(&requests[k]).unwrap_or_default(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::noise::SplitMix64;
    use game::simulate::random_request;

    fn requests(n: usize) -> Vec<SimulateRequest> {
        let mut rng = SplitMix64::new(7);
        (0..n).map(|_| random_request(&mut rng)).collect()
    }

    #[test]
    fn answers_with_the_native_bits_pass_and_are_tallied() {
        let reqs = requests(20);
        let answers: Vec<String> = reqs.iter().map(native_line).collect();
        let tally = check("echo", 7, &reqs, &answers).unwrap();
        assert_eq!(tally.errors, 0);
    }

    #[test]
    fn one_number_off_names_the_first_request_that_differs() {
        let reqs = requests(5);
        let mut answers: Vec<String> = reqs.iter().map(native_line).collect();
        let mut sim: serde_json::Value = serde_json::from_str(&answers[3]).unwrap();
        sim["duration"] = serde_json::json!(sim["duration"].as_f64().unwrap() + 1e-12);
        answers[3] = sim.to_string();
        let err = check("echo", 7, &reqs, &answers).unwrap_err();
        assert!(
            err.starts_with("1 of 5 requests differ; the first, request 3"),
            "{err}"
        );
        assert!(
            check("echo", 7, &reqs, &answers[..4]).is_err(),
            "a missing line"
        );
    }

    #[test]
    fn an_error_answer_is_compared_by_its_code_alone() {
        assert_eq!(
            normalise(r#"{"error": "too-fast", "message": "slower"}"#).unwrap(),
            r#"{"error":"too-fast"}"#
        );
        assert!(normalise("not json").is_err());
    }
}
