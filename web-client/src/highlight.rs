//! Highlights: which shots are worth seeing again, and how slowly. A live
//! match replays such a shot at once in slow motion ([`SLOW`], skippable);
//! the replay viewer lists the match's best shots by the pieces each
//! knocked off ([`best_shots`]).

use game::ShotOutcome;

/// The instant replay's speed: a quarter of real time.
pub const SLOW: f64 = 0.25;

/// Whether a shot earns an instant replay: it knocked off two or more
/// pieces, or it won a round.
pub fn worth_replaying(o: &ShotOutcome) -> bool {
    let won = |e: &game::RoundEnd| matches!(e.result, game::RoundResult::Won(_));
    o.knocked_off.len() >= 2 || o.round_end.as_ref().is_some_and(won)
}

/// The shots that knocked pieces off, most pieces first (earlier first
/// among equals), at most `n`: each shot's index in the match and its
/// count of pieces knocked off.
pub fn best_shots<'a>(
    outcomes: impl IntoIterator<Item = &'a ShotOutcome>,
    n: usize,
) -> Vec<(usize, usize)> {
    let mut shots: Vec<(usize, usize)> = outcomes
        .into_iter()
        .enumerate()
        .map(|(i, o)| (i, o.knocked_off.len()))
        .filter(|&(_, k)| k > 0)
        .collect();
    shots.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    shots.truncate(n);
    shots
}

#[cfg(test)]
mod tests {
    use super::*;
    use game::{Config, Game, PieceId, Shot, Side};
    use glam::DVec2;

    /// White's e-piece flicked straight up at `speed`: its outcome.
    fn flick(speed: f64) -> ShotOutcome {
        let mut game = Game::new(Config::default(), 7).unwrap();
        let piece = PieceId::new(Side::White, 4).unwrap();
        let shot = Shot::new(piece, DVec2::new(0.0, speed), game.config()).unwrap();
        game.play(Side::White, shot).unwrap().outcome
    }

    #[test]
    fn two_pieces_knocked_off_or_a_round_won_earn_a_replay_and_one_piece_does_not() {
        let mut o = flick(2.0);
        o.round_end = None;
        let one = o.knocked_off[0];
        o.knocked_off = vec![one];
        assert!(!worth_replaying(&o));
        o.knocked_off = vec![one, one];
        assert!(worth_replaying(&o));
        o.knocked_off.clear();
        assert!(!worth_replaying(&o));
    }

    #[test]
    fn the_best_shots_are_the_most_pieces_first_and_the_misses_left_out() {
        let mut shots = vec![flick(2.0), flick(2.0), flick(2.0), flick(2.0)];
        let p = shots[0].knocked_off[0];
        shots[0].knocked_off = vec![p];
        shots[1].knocked_off.clear();
        shots[2].knocked_off = vec![p, p, p];
        shots[3].knocked_off = vec![p];
        assert_eq!(best_shots(&shots, 5), vec![(2, 3), (0, 1), (3, 1)]);
        assert_eq!(best_shots(&shots, 1), vec![(2, 3)]);
    }
}
