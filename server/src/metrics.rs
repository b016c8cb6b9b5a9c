//! The server's Prometheus metrics, kept in `prometheus-client`'s metric
//! types (atomics for the counters and gauges, a short lock per
//! observation for the histograms) and written in the Prometheus text
//! format (version 0.0.4) by its encoder: connections, matches in memory
//! and live, shots resolved, refused client messages, and two histograms:
//! shot resolution time (physics and the store write, up to the broadcast)
//! and the whole server-side shot-to-broadcast time (from the frame's
//! arrival on its connection, so the wait in the match's queue counts too).
//! The other layers add theirs (the store's group commits, a cluster
//! node's share) to the same [`Registry`] before it is encoded once.

use prometheus_client::encoding::prometheus_text;
use prometheus_client::metrics::counter::{ConstCounter, Counter};
use prometheus_client::metrics::gauge::{ConstGauge, Gauge};
use prometheus_client::registry::Registry;
use std::time::Duration;

/// Upper bounds of the latency histograms' buckets, seconds.
pub const BUCKETS: [f64; 12] = [
    0.0005, 0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1.0, 2.5,
];

/// The `Content-Type` of the text [`encode`] writes.
pub const CONTENT_TYPE: &str = prometheus_text::CONTENT_TYPE;

/// The metrics registered in `registry` as Prometheus text. Counters are
/// registered without their `_total`, which the encoder appends; help
/// texts without their final period, which the registry appends.
pub fn encode(registry: &Registry) -> String {
    let mut out = String::new();
    prometheus_text::encode(&mut out, registry).expect("writing to a String does not fail");
    out
}

/// The server's counters and gauges.
#[derive(Debug, Default)]
pub struct Metrics {
    connections: Gauge,
    rooms: Gauge,
    live: Gauge,
    shots: Counter,
    refused: Counter,
    hosted_decisions: Counter,
    hosted_failures: Counter,
    resolution: Histogram,
    to_broadcast: Histogram,
}

/// A latency histogram over [`BUCKETS`].
#[derive(Debug, Clone)]
pub struct Histogram(prometheus_client::metrics::histogram::Histogram);

impl Default for Histogram {
    fn default() -> Self {
        Histogram(prometheus_client::metrics::histogram::Histogram::new(
            BUCKETS,
        ))
    }
}

impl Histogram {
    /// Counts one observation of `took`.
    pub fn observe(&self, took: Duration) {
        self.0.observe(took.as_secs_f64());
    }

    /// Registers the histogram in `registry` under `name`.
    pub fn register(&self, registry: &mut Registry, name: &str, help: &str) {
        registry.register(name, help, self.0.clone());
    }
}

impl Metrics {
    pub fn connection_opened(&self) {
        self.connections.inc();
    }
    pub fn connection_closed(&self) {
        self.connections.dec();
    }
    pub fn connections(&self) -> i64 {
        self.connections.get()
    }
    pub fn room_opened(&self) {
        self.rooms.inc();
    }
    pub fn room_closed(&self) {
        self.rooms.dec();
    }
    /// A match became live (`+1`) or stopped being live (`-1`).
    pub fn live_changed(&self, delta: i64) {
        self.live.inc_by(delta);
    }
    pub fn live(&self) -> i64 {
        self.live.get()
    }
    pub fn refused(&self) {
        self.refused.inc();
    }
    pub fn shots(&self) -> u64 {
        self.shots.get()
    }

    /// A hosted bot decided (`failed`: it gave no answer).
    pub fn hosted_decided(&self, failed: bool) {
        self.hosted_decisions.inc();
        if failed {
            self.hosted_failures.inc();
        }
    }

    /// A shot was resolved and stored in `took`.
    pub fn shot_resolved(&self, took: Duration) {
        self.shots.inc();
        self.resolution.observe(took);
    }

    /// A shot's outcome was handed to every connection's queue `took` after
    /// the shot's frame arrived.
    pub fn shot_broadcast(&self, took: Duration) {
        self.to_broadcast.observe(took);
    }

    /// Registers these metrics, and the process's CPU time and resident
    /// memory as they are now, in `registry`.
    pub fn register(&self, registry: &mut Registry) {
        registry.register(
            "chapaev_connections",
            "Open WebSocket connections",
            self.connections.clone(),
        );
        registry.register(
            "chapaev_matches_in_memory",
            "Matches held in memory (open, live, recently finished)",
            self.rooms.clone(),
        );
        registry.register(
            "chapaev_live_matches",
            "Matches with both seats taken and not over",
            self.live.clone(),
        );
        registry.register(
            "chapaev_shots_resolved",
            "Shots resolved and stored",
            self.shots.clone(),
        );
        registry.register(
            "chapaev_refused_messages",
            "Client messages answered with an error",
            self.refused.clone(),
        );
        registry.register(
            "chapaev_hosted_decisions",
            "Decisions of hosted bots (WebAssembly modules the server plays)",
            self.hosted_decisions.clone(),
        );
        registry.register(
            "chapaev_hosted_decision_failures",
            "Decisions of hosted bots that gave no answer (out of fuel, a trap, a bad answer)",
            self.hosted_failures.clone(),
        );
        if let Some(cpu) = cpu_seconds() {
            registry.register(
                "process_cpu_seconds",
                "CPU time the server process has used (user and system)",
                ConstCounter::new(cpu),
            );
        }
        if let Some(rss) = resident_bytes() {
            registry.register(
                "process_resident_memory_bytes",
                "Resident memory of the server process",
                ConstGauge::new(i64::try_from(rss).unwrap_or(i64::MAX)),
            );
        }
        self.resolution.register(
            registry,
            "chapaev_shot_resolution_seconds",
            "Time from a shot's turn in its match to its broadcast (physics and store write)",
        );
        self.to_broadcast.register(
            registry,
            "chapaev_shot_to_broadcast_seconds",
            "Time from a shot's frame arriving on its connection to its broadcast (queueing included)",
        );
    }

    /// These metrics alone as Prometheus text.
    pub fn render(&self) -> String {
        let mut registry = Registry::default();
        self.register(&mut registry);
        encode(&registry)
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

    #[test]
    fn names_help_and_types_are_those_of_the_prometheus_text_format() {
        let m = Metrics::default();
        m.refused();
        let text = m.render();
        for family in [
            "# HELP chapaev_connections Open WebSocket connections.\n\
             # TYPE chapaev_connections gauge\n\
             chapaev_connections 0\n",
            "# HELP chapaev_shots_resolved_total Shots resolved and stored.\n\
             # TYPE chapaev_shots_resolved_total counter\n\
             chapaev_shots_resolved_total 0\n",
            "# TYPE chapaev_refused_messages_total counter\n\
             chapaev_refused_messages_total 1\n",
            "# TYPE chapaev_shot_resolution_seconds histogram\n",
            "chapaev_shot_to_broadcast_seconds_bucket{le=\"1\"} 0\n\
             chapaev_shot_to_broadcast_seconds_bucket{le=\"2.5\"} 0\n\
             chapaev_shot_to_broadcast_seconds_bucket{le=\"+Inf\"} 0\n\
             chapaev_shot_to_broadcast_seconds_sum 0.0\n\
             chapaev_shot_to_broadcast_seconds_count 0\n",
        ] {
            assert!(text.contains(family), "{family}\nnot in\n{text}");
        }
        if cpu_seconds().is_some() {
            assert!(text.contains("# TYPE process_cpu_seconds_total counter\n"));
            assert!(text.contains("# TYPE process_resident_memory_bytes gauge\n"));
        }
        // Version 0.0.4, not OpenMetrics: no end marker.
        assert!(!text.contains("# EOF"), "{text}");
        assert!(CONTENT_TYPE.starts_with("text/plain; version=0.0.4"));
    }
}
