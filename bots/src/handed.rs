//! [`Handed`]: any bot's intended shots played through a person-like
//! [`Hand`] — the match's bias, more error on long shots and thin cuts, a
//! full power that can come out harder. The wrapper draws a new bias when
//! a match ends, and can keep a log of every throw (what was intended,
//! what was played, on which board) for measuring how a level misses.

use crate::bot::{Bot, Context, Decision};
use crate::hand::{Hand, HandModel};
use game::{Board, MatchRecord, MatchResult, Shot, ShotOutcome};

/// One shot as intended and as the hand played it.
#[derive(Clone, Debug, PartialEq)]
pub struct Throw {
    /// The board it was shot on.
    pub board: Board,
    /// What the bot chose.
    pub intended: Shot,
    /// What its hand made of it.
    pub played: Shot,
}

/// A bot whose shots are played by a person-like hand.
#[derive(Clone, Debug)]
pub struct Handed<B> {
    inner: B,
    hand: Hand,
    log: Option<Vec<Throw>>,
}

impl<B: Bot> Handed<B> {
    /// `inner`'s choices played by a hand of `model`, its bias and errors
    /// following from `seed` alone.
    pub fn new(inner: B, model: HandModel, seed: u64) -> Handed<B> {
        Handed {
            inner,
            hand: Hand::new(model, seed),
            log: None,
        }
    }

    /// The same, keeping a log of every throw ([`Handed::throws`]).
    pub fn logging(mut self) -> Handed<B> {
        self.log = Some(Vec::new());
        self
    }

    /// The throws logged so far (empty unless made with
    /// [`Handed::logging`]).
    pub fn throws(&self) -> &[Throw] {
        self.log.as_deref().unwrap_or(&[])
    }

    /// The bot that chooses.
    pub fn inner(&self) -> &B {
        &self.inner
    }

    /// The bot that chooses, to change.
    pub fn inner_mut(&mut self) -> &mut B {
        &mut self.inner
    }

    /// The hand.
    pub fn hand(&self) -> &Hand {
        &self.hand
    }

    /// The hand, to change.
    pub fn hand_mut(&mut self) -> &mut Hand {
        &mut self.hand
    }
}

impl<B: Bot> Bot for Handed<B> {
    fn decide(&mut self, ctx: &Context) -> Decision {
        match self.inner.decide(ctx) {
            Decision::Shot(intended) => {
                let board = &ctx.view.board;
                let played = self.hand.play(ctx.config(), board, &intended);
                if let Some(log) = self.log.as_mut() {
                    log.push(Throw {
                        board: board.clone(),
                        intended,
                        played,
                    });
                }
                Decision::Shot(played)
            }
            other => other,
        }
    }
    fn on_shot(&mut self, outcome: &ShotOutcome) {
        self.inner.on_shot(outcome)
    }
    fn on_match_over(&mut self, result: &MatchResult, record: &MatchRecord) {
        self.hand.new_match();
        self.inner.on_match_over(result, record)
    }
}
