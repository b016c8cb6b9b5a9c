//! Prometheus metrics in the text exposition format, kept in atomics (no
//! locks on the hot path): connections, matches in memory and live, shots
//! resolved, refused client messages, and two histograms: shot resolution
//! time (physics and the store write, up to the broadcast) and the whole
//! server-side shot-to-broadcast time (from the frame's arrival on its
//! connection, so the wait in the match's queue counts too).

use std::fmt::Write as _;
use std::sync::atomic::{AtomicI64, AtomicU64, Ordering};
use std::time::Duration;

/// Upper bounds of the latency histograms' buckets, seconds.
pub const BUCKETS: [f64; 12] = [
    0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1.0, 2.5,
];

/// The server's counters and gauges.
#[derive(Debug, Default)]
pub struct Metrics {
    connections: AtomicI64,
    rooms: AtomicI64,
    live: AtomicI64,
    shots: AtomicU64,
    refused: AtomicU64,
    resolution: Histogram,
    to_broadcast: Histogram,
}

/// A latency histogram over [`BUCKETS`] (cumulative, as Prometheus wants).
#[derive(Debug, Default)]
pub struct Histogram {
    buckets: [AtomicU64; BUCKETS.len()],
    sum_nanos: AtomicU64,
    count: AtomicU64,
}

impl Histogram {
    /// Counts one observation of `took`.
    pub fn observe(&self, took: Duration) {
        let secs = took.as_secs_f64();
        for (bound, bucket) in BUCKETS.iter().zip(&self.buckets) {
            if secs <= *bound {
                bucket.fetch_add(1, Ordering::Relaxed);
            }
        }
        let nanos = u64::try_from(took.as_nanos()).unwrap_or(u64::MAX);
        self.sum_nanos.fetch_add(nanos, Ordering::Relaxed);
        self.count.fetch_add(1, Ordering::Relaxed);
    }

    /// Appends the histogram as Prometheus text under `name`.
    pub fn render(&self, out: &mut String, name: &str, help: &str) {
        let _ = writeln!(out, "# HELP {name} {help}\n# TYPE {name} histogram");
        for (bound, bucket) in BUCKETS.iter().zip(&self.buckets) {
            let _ = writeln!(
                out,
                "{name}_bucket{{le=\"{bound}\"}} {}",
                bucket.load(Ordering::Relaxed)
            );
        }
        let count = self.count.load(Ordering::Relaxed);
        let _ = writeln!(out, "{name}_bucket{{le=\"+Inf\"}} {count}");
        let sum = self.sum_nanos.load(Ordering::Relaxed) as f64 / 1e9;
        let _ = writeln!(out, "{name}_sum {sum}\n{name}_count {count}");
    }
}

impl Metrics {
    pub fn connection_opened(&self) {
        self.connections.fetch_add(1, Ordering::Relaxed);
    }
    pub fn connection_closed(&self) {
        self.connections.fetch_sub(1, Ordering::Relaxed);
    }
    pub fn connections(&self) -> i64 {
        self.connections.load(Ordering::Relaxed)
    }
    pub fn room_opened(&self) {
        self.rooms.fetch_add(1, Ordering::Relaxed);
    }
    pub fn room_closed(&self) {
        self.rooms.fetch_sub(1, Ordering::Relaxed);
    }
    /// A match became live (`+1`) or stopped being live (`-1`).
    pub fn live_changed(&self, delta: i64) {
        self.live.fetch_add(delta, Ordering::Relaxed);
    }
    pub fn live(&self) -> i64 {
        self.live.load(Ordering::Relaxed)
    }
    pub fn refused(&self) {
        self.refused.fetch_add(1, Ordering::Relaxed);
    }
    pub fn shots(&self) -> u64 {
        self.shots.load(Ordering::Relaxed)
    }

    /// A shot was resolved and stored in `took`.
    pub fn shot_resolved(&self, took: Duration) {
        self.shots.fetch_add(1, Ordering::Relaxed);
        self.resolution.observe(took);
    }

    /// A shot's outcome was handed to every connection's queue `took` after
    /// the shot's frame arrived.
    pub fn shot_broadcast(&self, took: Duration) {
        self.to_broadcast.observe(took);
    }

    /// The metrics as Prometheus text.
    pub fn render(&self) -> String {
        let mut out = String::new();
        let mut gauge = |name: &str, help: &str, kind: &str, value: String| {
            let _ = writeln!(
                out,
                "# HELP {name} {help}\n# TYPE {name} {kind}\n{name} {value}"
            );
        };
        gauge(
            "chapaev_connections",
            "Open WebSocket connections.",
            "gauge",
            self.connections().to_string(),
        );
        gauge(
            "chapaev_matches_in_memory",
            "Matches held in memory (open, live, recently finished).",
            "gauge",
            self.rooms.load(Ordering::Relaxed).to_string(),
        );
        gauge(
            "chapaev_live_matches",
            "Matches with both seats taken and not over.",
            "gauge",
            self.live().to_string(),
        );
        gauge(
            "chapaev_shots_resolved_total",
            "Shots resolved and stored.",
            "counter",
            self.shots().to_string(),
        );
        gauge(
            "chapaev_refused_messages_total",
            "Client messages answered with an error.",
            "counter",
            self.refused.load(Ordering::Relaxed).to_string(),
        );
        if let Some(cpu) = cpu_seconds() {
            gauge(
                "process_cpu_seconds_total",
                "CPU time the server process has used (user and system).",
                "counter",
                cpu.to_string(),
            );
        }
        if let Some(rss) = resident_bytes() {
            gauge(
                "process_resident_memory_bytes",
                "Resident memory of the server process.",
                "gauge",
                rss.to_string(),
            );
        }
        self.resolution.render(
            &mut out,
            "chapaev_shot_resolution_seconds",
            "Time from a shot's turn in its match to its broadcast (physics and store write).",
        );
        self.to_broadcast.render(
            &mut out,
            "chapaev_shot_to_broadcast_seconds",
            "Time from a shot's frame arriving on its connection to its broadcast (queueing included).",
        );
        out
    }
}

/// CPU time (user and system) this process has used, seconds, from
/// `/proc/self/stat` (Linux only).
pub fn cpu_seconds() -> Option<f64> {
    cpu_seconds_in(&std::fs::read_to_string("/proc/self/stat").ok()?)
}

/// CPU seconds from the text of a `/proc/PID/stat`: fields 14 and 15
/// (`utime`, `stime`) in clock ticks of 1/100 s. The command name, field 2,
/// may hold spaces, so fields are counted after its closing parenthesis.
pub fn cpu_seconds_in(stat: &str) -> Option<f64> {
    let after_name = &stat[stat.rfind(')')? + 1..];
    let mut fields = after_name.split_whitespace().skip(11);
    let user: u64 = fields.next()?.parse().ok()?;
    let system: u64 = fields.next()?.parse().ok()?;
    Some((user + system) as f64 / 100.0)
}

/// The process's resident memory, from `/proc/self/statm` (Linux only).
pub fn resident_bytes() -> Option<u64> {
    let statm = std::fs::read_to_string("/proc/self/statm").ok()?;
    let pages: u64 = statm.split_whitespace().nth(1)?.parse().ok()?;
    Some(pages * 4096)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn histogram_buckets_are_cumulative_and_text_is_prometheus() {
        let m = Metrics::default();
        m.shot_resolved(Duration::from_micros(700));
        m.shot_resolved(Duration::from_millis(30));
        m.connection_opened();
        m.live_changed(1);
        let text = m.render();
        assert!(text.contains("chapaev_connections 1\n"), "{text}");
        assert!(text.contains("chapaev_live_matches 1\n"));
        assert!(text.contains("chapaev_shots_resolved_total 2\n"));
        assert!(text.contains("chapaev_shot_resolution_seconds_bucket{le=\"0.0005\"} 0\n"));
        assert!(text.contains("chapaev_shot_resolution_seconds_bucket{le=\"0.001\"} 1\n"));
        assert!(text.contains("chapaev_shot_resolution_seconds_bucket{le=\"0.05\"} 2\n"));
        assert!(text.contains("chapaev_shot_resolution_seconds_bucket{le=\"+Inf\"} 2\n"));
        assert!(text.contains("chapaev_shot_resolution_seconds_count 2\n"));
        // The arrival-to-broadcast histogram is its own.
        assert!(text.contains("chapaev_shot_to_broadcast_seconds_count 0\n"));
        m.shot_broadcast(Duration::from_millis(3));
        let text = m.render();
        assert!(text.contains("chapaev_shot_to_broadcast_seconds_bucket{le=\"0.0025\"} 0\n"));
        assert!(text.contains("chapaev_shot_to_broadcast_seconds_bucket{le=\"0.005\"} 1\n"));
        assert!(text.contains("chapaev_shot_to_broadcast_seconds_count 1\n"));
        assert!(text.contains("chapaev_shots_resolved_total 2\n"));
    }

    #[test]
    fn cpu_time_is_read_past_a_command_name_with_spaces() {
        let stat = "4242 (a (b) c) S 1 4242 4242 0 -1 4194560 \
                    100 0 0 0 250 75 0 0 20 0 9 0 123 456 789";
        assert_eq!(cpu_seconds_in(stat), Some(3.25));
        assert_eq!(cpu_seconds_in("no parenthesis"), None);
        assert_eq!(cpu_seconds_in("1 (x) S 1 2"), None);
    }
}
