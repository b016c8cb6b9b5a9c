//! `greedy`: tries many candidate shots ([`crate::candidates`]) on the
//! [`crate::simulator::Simulator`], as aimed, and plays the one whose result
//! [`crate::eval::after_shot`] scores best — material, the turn kept, the
//! safety of its own pieces. One ply, no look-ahead, no noise.

use crate::bot::{Ask, Bot, Context, Decision};
use crate::candidates::Spread;
use crate::eval::best_shot;
use game::MatchView;

/// The greedy bot.
#[derive(Clone, Debug)]
pub struct Greedy {
    spread: Spread,
}

impl Default for Greedy {
    fn default() -> Self {
        Greedy {
            spread: Spread::wide(),
        }
    }
}

impl Greedy {
    /// A greedy bot trying `spread`'s candidates.
    pub fn with_spread(spread: Spread) -> Greedy {
        Greedy { spread }
    }
}

/// Black's pie decision for a bot without a generator of its own: the
/// playouts of [`crate::pie`] seeded by the position alone.
pub fn pie_swap(view: &MatchView) -> bool {
    crate::pie::swap(
        view,
        &crate::pie::PieSettings::default(),
        crate::pie::position_seed(view),
    )
}

impl Bot for Greedy {
    fn decide(&mut self, ctx: &Context) -> Decision {
        if ctx.ask() == Some(Ask::Pie) {
            return Decision::Pie {
                swap: pie_swap(ctx.view),
            };
        }
        match best_shot(ctx.config(), &ctx.view.board, ctx.me, &self.spread) {
            Some((shot, _)) => Decision::Shot(shot),
            None => Decision::Resign,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulator::Simulator;
    use game::{Config, Game, Phase, Side};
    use std::time::Duration;

    #[test]
    fn greedy_knocks_an_enemy_off_from_the_opening_and_keeps_the_turn() {
        let view = Game::new(Config::default(), 1).unwrap().view();
        let ctx = Context::new(&view, Side::White, Duration::from_secs(5));
        let Decision::Shot(shot) = Greedy::default().decide(&ctx) else {
            panic!("greedy shoots");
        };
        let after = Simulator::new(&view).play(Side::White, &shot).unwrap();
        assert!(after.lost(Side::Black) >= 1, "{after:?}");
        assert_eq!(after.lost(Side::White), 0);
        assert_eq!(view.phase, Phase::Shooting);
    }
}
