//! The end-of-match screen over the board: the result as the viewer reads
//! it, how it was decided, the rounds, the shots, and one press to a
//! rematch, the replay or closing it. Its words are worked out without
//! drawing ([`words`]); its places come from [`super::layout::end_screen`].

use super::layout;
use crate::i18n::t;
use crate::story::{side_key, side_name, Score};
use crate::ui::{self, colors, Ui};
use game::{MatchResult, MatchView, Side, WinReason};
use macroquad::prelude::{draw_rectangle, Color, Rect};

/// What the end screen says.
#[derive(Clone, Debug, PartialEq)]
pub struct Words {
    pub title: String,
    pub color: Color,
    pub reason: String,
    pub rounds: String,
    pub counts: String,
}

/// The end screen's words for `result`, seen from `me`'s side.
pub fn words(result: MatchResult, me: Option<Side>, score: &Score, v: &MatchView) -> Words {
    let (title, color) = match (result.winner(), me) {
        (None, _) => (t!("end-drawn"), colors::TEXT),
        (Some(wn), Some(me)) if wn == me => (t!("end-you-won"), colors::GOOD),
        (Some(_), Some(_)) => (t!("end-you-lost"), colors::DANGER),
        (Some(wn), None) => (t!("end-side-won", side = side_key(wn)), colors::ACCENT),
    };
    Words {
        title,
        color,
        reason: reason(result),
        rounds: score.rounds_line(),
        counts: format!(
            "{} · {}",
            t!("shots-count", count = v.shots),
            t!("rounds-count", count = v.round)
        ),
    }
}

/// How the match was decided, in words.
pub fn reason(r: MatchResult) -> String {
    match r {
        MatchResult::Draw => t!("end-reason-draw"),
        MatchResult::Won { side, reason } => {
            let side = side_name(side);
            match reason {
                WinReason::FarEdge => t!("end-reason-far-edge", side = side),
                WinReason::QuickMatch => t!("end-reason-quick", side = side),
                WinReason::Resignation => t!("end-reason-resignation", side = side),
                WinReason::Timeouts => t!("end-reason-timeouts", side = side),
                WinReason::Abandoned => t!("end-reason-abandoned", side = side),
            }
        }
    }
}

/// Draws the end screen over the board `area`; a `rematch` button (its
/// label and whether it can be pressed) for a seated player. The names of
/// the buttons pressed: `end-rematch`, `end-replay`, `end-close`.
pub fn show(
    ui: &mut Ui,
    area: Rect,
    w: &Words,
    rematch: Option<(&str, bool)>,
) -> Vec<&'static str> {
    let l = layout::end_screen(area, rematch.is_some());
    let r = l.r;
    draw_rectangle(
        r.x - 4.0,
        r.y - 4.0,
        r.w + 8.0,
        r.h + 8.0,
        Color::new(0.0, 0.0, 0.0, 0.45),
    );
    ui::panel(r);
    ui::text_in(&w.title, l.x, r.y + 14.0, 30.0, l.w, w.color);
    ui::text_in(&w.reason, l.x, r.y + 54.0, 15.0, l.w, colors::MUTED);
    ui::text_in(&w.rounds, l.x, r.y + 80.0, 17.0, l.w, colors::TEXT);
    ui::text_in(&w.counts, l.x, r.y + 104.0, 17.0, l.w, colors::TEXT);
    let mut pressed = Vec::new();
    if let (Some((label, enabled)), Some(b)) = (rematch, l.rematch) {
        if ui.button_styled("end-rematch", label, b, enabled, false) {
            pressed.push("end-rematch");
        }
    }
    if ui.button("end-replay", &t!("replay"), l.replay) {
        pressed.push("end-replay");
    }
    if ui.button("end-close", &t!("close"), l.close) {
        pressed.push("end-close");
    }
    pressed
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Config, Game};

    #[test]
    fn the_title_is_the_viewers_result() {
        let v = Game::new(Config::default(), 7).unwrap().view();
        let won = MatchResult::Won {
            side: Side::Black,
            reason: WinReason::Timeouts,
        };
        let score = Score::of(std::iter::empty::<&game::ShotOutcome>());
        assert_eq!(words(won, Some(Side::Black), &score, &v).title, "You won!");
        assert_eq!(words(won, Some(Side::White), &score, &v).title, "You lost");
        assert_eq!(words(won, None, &score, &v).title, "Black won");
        let drawn = words(MatchResult::Draw, Some(Side::White), &score, &v);
        assert_eq!(drawn.title, "Drawn");
        assert_eq!(drawn.reason, "Both sides' last pieces fell together");
        assert_eq!(
            words(won, None, &score, &v).reason,
            "Black won: the other side ran out of time three times"
        );
        assert_eq!(words(won, None, &score, &v).counts, "0 shots · 1 round");
    }
}
