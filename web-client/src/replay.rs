//! The replay viewer: a finished match's record, replayed bit for bit by
//! the game crate, shown on one timeline that can be scrubbed, played
//! forwards or backwards at -2x to 4x, and jumped shot by shot. Every
//! moment is computed from the exact films, so scrubbing is instant. The
//! heading says whether the match's noise verifies against the commitment
//! published before its first shot ([`game::verify`]). Played forwards,
//! the shots sound as they did live ([`sounds_between`]); scrubbed or
//! played backwards, they are silent.

use crate::api::{Api, Pending};
use crate::clip::{Clip, Frame};
use crate::draw;
use crate::highlight;
use crate::i18n::t;
use crate::platform::{self, Sound};
use crate::route::Route;
use crate::screen::Screen;
use crate::timeline::Timeline;
use crate::ui::{self, colors, Ui};
use crate::viewport::Viewport;
use game::{MatchResult, MatchView, Replay as GameReplay, Side, WinReason};
use macroquad::prelude::*;

mod layout;

use layout::Mode;

/// How many best shots are listed.
const BEST: usize = 3;

/// The title's size (its lines are three units apart).
const TITLE_SIZE: f32 = 19.0;

/// The title and the heading of the sideways layout's column, `width`
/// wide and at most `room` tall: in lines, at the largest size from 15
/// units down to 12 at which all of them fit. The size and the lines.
fn column_text(title: &str, head: &str, width: f32, room: f32) -> (f32, Vec<String>, Vec<String>) {
    let mut size = 15.0;
    loop {
        let t = crate::help::wrap(title, size, width);
        let h = crate::help::wrap(head, size, width);
        let tall = (t.len() + h.len()) as f32 * (size + 3.0) + 4.0;
        if tall <= room || size <= ui::MIN_TEXT {
            return (size, t, h);
        }
        size -= 1.0;
    }
}

struct Loaded {
    replay: GameReplay,
    clips: Vec<Clip>,
    timeline: Timeline,
    /// The best shots: each one's index and the pieces it knocked off.
    best: Vec<(usize, usize)>,
    /// What [`game::verify`] said of the record, in words.
    fairness: String,
}

/// [`game::verify`]'s verdict on a record, in a few words for the heading.
fn fairness(record: &game::MatchRecord) -> String {
    match game::verify(record) {
        Ok(v) => t!("replay-noise-verified", shots = v.shots),
        Err(game::VerifyError::Uncommitted { .. }) => t!("replay-noise-uncommitted"),
        Err(e) => t!("replay-noise-failed", code = e.code()),
    }
}

enum State {
    Fetching(Pending<String>),
    Ready(Box<Loaded>),
    Failed(String),
}

pub struct Replay {
    match_id: String,
    state: State,
    /// The match's summary, being fetched for its players' names.
    summary: Option<Pending<crate::api::Summary>>,
    /// Who played whom ("Petka vs computer (easy)"), once known.
    players: Option<String>,
    t: f64,
    speed: f64,
    playing: bool,
    scrubbing: bool,
}

impl Replay {
    pub fn new(api: Api, match_id: String) -> Replay {
        Replay {
            state: State::Fetching(api.record(&match_id)),
            summary: Some(api.summary(&match_id)),
            players: None,
            match_id,
            t: 0.0,
            speed: 1.0,
            playing: true,
            scrubbing: false,
        }
    }

    /// Replays a record's JSON text.
    fn load(text: &str) -> Result<Loaded, String> {
        let replay =
            GameReplay::from_json(text).map_err(|e| t!("replay-cannot", error = e.to_string()))?;
        let clips: Vec<Clip> = (0..replay.shot_count())
            .filter_map(|n| {
                Some(Clip::new(
                    replay.outcome(n)?.clone(),
                    replay.film(n)?.clone(),
                ))
            })
            .collect();
        let timeline = Timeline::new(clips.iter().map(Clip::duration));
        Ok(Loaded {
            best: highlight::best_shots(clips.iter().map(|c| &c.outcome), BEST),
            fairness: fairness(replay.record()),
            replay,
            clips,
            timeline,
        })
    }
}

/// What to show at match time `t`: the view of the match then and the frame.
/// The sounds of the match between times `from` and `to` of `timeline`
/// (the shots of `clips`): each shot's flick as the time reaches its start,
/// then its clacks and falls ([`Clip::sounds`]). Nothing unless `to` is
/// after `from`.
fn sounds_between(clips: &[Clip], timeline: &Timeline, from: f64, to: f64) -> Vec<Sound> {
    let mut sounds = Vec::new();
    if to <= from {
        return sounds;
    }
    let first = timeline.locate(from).map_or(0, |(n, _)| n);
    let last = timeline.locate(to).map_or(0, |(n, _)| n);
    for (n, clip) in clips.iter().enumerate().take(last + 1).skip(first) {
        let start = timeline.start(n);
        if (from..to).contains(&start) {
            sounds.push(Sound::Flick);
        }
        sounds.extend(clip.sounds(from - start, to - start));
    }
    sounds
}

fn at(l: &Loaded, t: f64) -> (MatchView, Frame, Option<usize>) {
    match l.timeline.locate(t) {
        Some((n, within)) => {
            let view = l
                .replay
                .view_before_shot(n)
                .cloned()
                .unwrap_or_else(|| l.replay.game().view());
            (view, l.clips[n].frame(within), Some(n))
        }
        None => {
            let view = l.replay.game().view();
            let frame = Frame {
                pieces: view.board.pieces().iter().map(|p| (p.id, p.pos)).collect(),
                ..Frame::default()
            };
            (view, frame, None)
        }
    }
}

/// How the match ended, in words.
fn result_line(r: MatchResult) -> String {
    match r {
        MatchResult::Draw => t!("replay-result-drawn"),
        MatchResult::Won { side, reason } => {
            let how = match reason {
                WinReason::FarEdge => "far-edge",
                WinReason::QuickMatch => "quick",
                WinReason::Resignation => "resignation",
                WinReason::Timeouts => "timeouts",
                WinReason::Abandoned => "abandoned",
            };
            t!(
                "replay-result-won",
                side = crate::story::side_key(side),
                how = how
            )
        }
    }
}

impl Screen for Replay {
    fn frame(&mut self, ui: &mut Ui, dt: f64) -> Option<Route> {
        if let Some(r) = self.summary.as_mut().and_then(Pending::poll) {
            // Without an answer the heading names the match by its id.
            self.players = r.ok().map(|s| crate::lobby::describe(&s).0);
            self.summary = None;
        }
        if let State::Fetching(p) = &mut self.state {
            if let Some(r) = p.poll() {
                self.state = match r.and_then(|text| Replay::load(&text)) {
                    Ok(l) => State::Ready(Box::new(l)),
                    Err(e) => State::Failed(e),
                };
            }
        }
        let (w, h) = crate::scale::size().into();
        let mode = layout::mode(w, h);
        let top = layout::top(w, h);
        let lobby = top.lobby;
        let l = match &self.state {
            State::Ready(l) => l,
            State::Fetching(_) => {
                ui::text_centred(
                    &t!("replay-loading"),
                    Rect::new(0.0, 0.0, w, h),
                    24.0,
                    colors::MUTED,
                );
                return ui
                    .button("lobby", &t!("lobby"), lobby)
                    .then_some(Route::Lobby);
            }
            State::Failed(e) => {
                for (i, line) in crate::help::wrap(e, 20.0, w - 24.0).iter().enumerate() {
                    ui::text(line, 12.0, 64.0 + i as f32 * 24.0, 20.0, colors::DANGER);
                }
                return ui
                    .button("lobby", &t!("lobby"), lobby)
                    .then_some(Route::Lobby);
            }
        };
        if self.playing && !self.scrubbing {
            let before = self.t;
            self.t = l.timeline.step(self.t, dt, self.speed);
            if crate::play::sound_on() {
                for s in sounds_between(&l.clips, &l.timeline, before, self.t) {
                    platform::play_sound(s);
                }
            }
            let at_end = self.speed > 0.0 && self.t >= l.timeline.total();
            let at_start = self.speed < 0.0 && self.t <= 0.0;
            if at_end || at_start {
                self.playing = false;
            }
        }
        let title = match &self.players {
            Some(players) => t!(
                "replay-title-players",
                players = players.as_str(),
                fairness = l.fairness.as_str()
            ),
            None => t!(
                "replay-title",
                id = self.match_id.as_str(),
                fairness = l.fairness.as_str()
            ),
        };
        let (view, frame, shot) = at(l, self.t);
        // Heading: which shot, who, the round, pieces left.
        let count = |s: Side| frame.pieces.iter().filter(|(p, _)| p.side() == s).count();
        let head = match shot {
            Some(n) => {
                let o = &l.clips[n].outcome;
                t!(
                    "replay-head",
                    shot = n + 1,
                    shots = l.clips.len(),
                    round = o.round,
                    side = crate::story::side_key(o.shooter),
                    piece = o.piece.to_string(),
                    white = count(Side::White),
                    black = count(Side::Black)
                )
            }
            None => t!("replay-no-shots"),
        };
        let head = match l.replay.game().result() {
            Some(r) if self.t >= l.timeline.total() => format!("{head} · {}", result_line(r)),
            _ => head,
        };
        // The title and the heading in lines (title, heading), each line's
        // top, size and colour, and where the heading ends.
        let mut lines: Vec<(String, f32, f32, Color)> = Vec::new();
        let head_h = match mode {
            Mode::Side => {
                // The column right of the board: both in as many lines as
                // they take, smaller where the column is short.
                let (size, t_lines, h_lines) =
                    column_text(&title, &head, top.title.w, top.heading.h);
                let mut y = top.title.y;
                for line in t_lines {
                    lines.push((line, y, size, colors::ACCENT));
                    y += size + 3.0;
                }
                y += 4.0;
                for line in h_lines {
                    lines.push((line, y, size, colors::TEXT));
                    y += size + 3.0;
                }
                0.0
            }
            _ => {
                // The title beside the buttons, in as many lines as it
                // takes; the heading below it (a narrow window: below the
                // buttons too, in as many lines as it takes).
                let step = TITLE_SIZE + 3.0;
                let t_lines = crate::help::wrap(&title, TITLE_SIZE, top.title.w);
                let title_end = top.title.y + t_lines.len() as f32 * step;
                for (i, line) in t_lines.into_iter().enumerate() {
                    let y = top.title.y + i as f32 * step;
                    lines.push((line, y, TITLE_SIZE, colors::ACCENT));
                }
                if mode == Mode::Narrow {
                    let mut y = title_end.max(lobby.y + lobby.h) + 2.0;
                    for line in crate::help::wrap(&head, 14.0, top.heading.w) {
                        lines.push((line, y, 14.0, colors::TEXT));
                        y += 18.0;
                    }
                    y + 2.0
                } else {
                    let y = title_end + 4.0;
                    lines.push((head.clone(), y, 15.0, colors::TEXT));
                    (y + 22.0).max(60.0)
                }
            }
        };
        // The board between the heading and the control bar (at the left
        // of the column, sideways).
        let board = layout::board(w, h, head_h);
        let vp = Viewport::fit_square(view.config.board_size(), board, 24.0, false);
        draw::board(&vp, view.config.board_size());
        let shooter = shot.map(|n| l.clips[n].outcome.piece);
        draw::frame(&vp, view.config.piece_radius, &frame, |p| {
            (Some(p) == shooter).then_some(colors::ACCENT)
        });
        // The heading stays above the board (the board is drawn first, so
        // a piece sliding off it goes under the heading and the bar).
        if mode == Mode::Side {
            draw_rectangle(board.w, 0.0, w - board.w, h, colors::BACKGROUND);
        } else {
            draw_rectangle(0.0, 0.0, w, head_h, colors::BACKGROUND);
        }
        crate::i18n::switch(ui, top.lang, top.short_lang);
        let text_w = top.heading.w;
        for (line, y, size, color) in &lines {
            // A line longer than its room (the wide heading beside the
            // buttons) is cut, and reported so.
            ui::text(
                &ui::fit(line, *size, text_w),
                top.title.x,
                *y,
                *size,
                *color,
            );
        }
        let mut go = ui
            .button("lobby", &t!("lobby"), lobby)
            .then_some(Route::Lobby);
        // The best shots down the board's left edge: each jumps to its
        // shot, in slow motion.
        let best = layout::best(w, h, head_h, l.best.len());
        if !l.best.is_empty() && mode == Mode::Wide {
            ui::text(
                &t!("replay-best-shots"),
                12.0,
                head_h + 6.0,
                15.0,
                colors::MUTED,
            );
        }
        for (i, (&(n, k), r)) in l.best.iter().zip(best).enumerate() {
            let label = t!("replay-best-shot", shot = n + 1, off = k);
            if ui.button(&format!("best-{i}"), &label, r) {
                self.t = l.timeline.start(n);
                self.speed = highlight::SLOW;
                self.playing = true;
            }
        }
        // The control bar: timeline, play/pause, shot jumps, speeds.
        let c = layout::controls(w, h);
        ui::panel(c.panel);
        let track = c.track;
        let total = l.timeline.total().max(1e-9);
        for n in 0..l.timeline.shots() {
            let x = track.x + track.w * (l.timeline.start(n) / total) as f32;
            draw_line(
                x,
                track.y + 4.0,
                x,
                track.y + track.h - 4.0,
                1.0,
                colors::MUTED,
            );
        }
        let before = self.t;
        let t = ui.slider("timeline", self.t, 0.0, total, track);
        self.scrubbing = ui.input.down && t != before;
        self.t = t;
        // The shot jumps say what they do (their words on two lines where
        // the row is narrow). The row's labels share one size.
        if ui.button("previous-shot", &t!("replay-previous-shot"), c.previous) {
            self.t = l.timeline.previous_shot(self.t);
        }
        let label = if self.playing {
            t!("replay-pause")
        } else {
            t!("replay-play")
        };
        if ui.button("play-pause", &label, c.play) {
            if !self.playing && self.speed > 0.0 && self.t >= l.timeline.total() {
                self.t = 0.0;
            }
            self.playing = !self.playing;
        }
        if ui.button("next-shot", &t!("replay-next-shot"), c.next) {
            self.t = l.timeline.next_shot(self.t);
        }
        ui::text_in(
            &t!(
                "replay-clock",
                at = format!("{:.1}", self.t),
                total = format!("{:.1}", l.timeline.total())
            ),
            c.clock.x,
            c.clock.y,
            c.clock.h,
            c.clock.w,
            colors::TEXT,
        );
        // One label size for the row, so "0.25x" is not smaller than "1x".
        let labels: Vec<String> = c.speeds.iter().map(|s| format!("{s}x")).collect();
        if let Some(&first) = c.speed_buttons.first() {
            ui.even_labels(&labels, first, |ui| {
                for ((&s, label), r) in c.speeds.iter().zip(&labels).zip(&c.speed_buttons) {
                    if ui.button_styled(&format!("speed{s}"), label, *r, true, self.speed == s) {
                        self.speed = s;
                        self.playing = true;
                    }
                }
            });
        }
        if is_key_pressed(KeyCode::Space) {
            self.playing = !self.playing;
        }
        if is_key_pressed(KeyCode::Right) {
            self.t = l.timeline.next_shot(self.t);
        }
        if is_key_pressed(KeyCode::Left) {
            self.t = l.timeline.previous_shot(self.t);
        }
        if go.is_none() && is_key_pressed(KeyCode::Escape) {
            go = Some(Route::Lobby);
        }
        go
    }

    fn name(&self) -> &'static str {
        "replay"
    }

    fn animating(&self) -> bool {
        self.playing
    }

    fn report(&self) -> serde_json::Map<String, serde_json::Value> {
        let mut m = serde_json::Map::new();
        m.insert("match_id".into(), self.match_id.clone().into());
        m.insert("t".into(), self.t.into());
        if let State::Ready(l) = &self.state {
            m.insert("shots".into(), l.clips.len().into());
            m.insert("total".into(), l.timeline.total().into());
            m.insert("best_shots".into(), serde_json::json!(l.best));
            m.insert("speed".into(), self.speed.into());
        }
        m.insert("players".into(), self.players.clone().into());
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ::glam::DVec2;
    use game::{Config, Game, PieceId, Shot};

    #[test]
    fn the_control_bar_reads_at_a_comfortable_size_on_a_desktop_in_both_languages() {
        use crate::i18n::{message_in, Lang};
        use crate::test_geometry::font_width;
        for lang in [Lang::En, Lang::Ru] {
            for play in ["replay-play", "replay-pause"] {
                // A 1280 x 800 browser window, in layout units.
                let w = 1280.0 / crate::scale::zoom_for(1280.0, 800.0);
                let (jump, play_w, speed) = layout::bar_widths(w);
                let text = |id: &str| message_in(lang, id).expect("the message exists");
                let mut labels = vec![
                    (text("replay-previous-shot"), jump),
                    (text(play), play_w),
                    (text("replay-next-shot"), jump),
                ];
                labels.extend(layout::SPEEDS.map(|s| (format!("{s}x"), speed)));
                let mut x = 20.0;
                let buttons: Vec<(&str, Rect)> = labels
                    .iter()
                    .map(|(label, w)| {
                        let r = Rect::new(x, 700.0, *w, ui::TOUCH);
                        x += w + 8.0;
                        (label.as_str(), r)
                    })
                    .collect();
                let sizes = ui::group_label_sizes(&buttons, font_width);
                eprintln!(
                    "replay {w} units wide {lang:?} {play}: the bar's labels at {}",
                    sizes[0]
                );
                assert!(sizes.iter().all(|s| *s >= 16.0), "{lang:?}: {sizes:?}");
                // The bar with the clock's room fits the window.
                assert!(x + 120.0 <= w);
            }
        }
    }

    /// Two shots of White straight up the board, each knocking a piece
    /// off, as clips on their timeline.
    fn two_shots() -> (Vec<Clip>, Timeline) {
        let config = Config::default();
        let mut g = Game::new(config.clone(), 7).unwrap();
        let clips: Vec<Clip> = [0, 1]
            .into_iter()
            .map(|k| {
                let piece = PieceId::new(Side::White, k).unwrap();
                let shot = Shot::new(piece, DVec2::new(0.0, 2.0), &config).unwrap();
                let p = g.play(Side::White, shot).unwrap();
                Clip::new(p.outcome, p.film)
            })
            .collect();
        let timeline = Timeline::new(clips.iter().map(Clip::duration));
        (clips, timeline)
    }

    #[test]
    fn a_replay_played_forwards_sounds_every_shot_once_and_backwards_is_silent() {
        let (clips, timeline) = two_shots();
        let mut heard = Vec::new();
        let mut t = 0.0;
        while t < timeline.total() {
            let next = timeline.step(t, 1.0 / 60.0, 1.0);
            heard.extend(sounds_between(&clips, &timeline, t, next));
            t = next;
        }
        let flicks = heard.iter().filter(|s| **s == Sound::Flick).count();
        assert_eq!(flicks, 2);
        let falls = heard.iter().filter(|s| **s == Sound::Fall).count();
        let knocked: usize = clips.iter().map(|c| c.outcome.knocked_off.len()).sum();
        assert_eq!(falls, knocked);
        assert!(heard.iter().any(|s| matches!(s, Sound::Clack { .. })));
        // One big step across both shots hears both flicks too.
        let all = sounds_between(&clips, &timeline, 0.0, timeline.total());
        assert_eq!(all.iter().filter(|s| **s == Sound::Flick).count(), 2);
        // Backwards: nothing.
        assert!(sounds_between(&clips, &timeline, timeline.total(), 0.0).is_empty());
    }
}
