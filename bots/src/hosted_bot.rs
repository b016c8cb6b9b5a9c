//! A WebAssembly bot ([`hosted::BotModule`]) as a [`Bot`]: each decision
//! runs in a fresh instance under the module's fuel budget, its random
//! stream derived from the match's noise secret, so a match it plays
//! replays exactly from its record. A decision that fails (out of fuel, a
//! trap, a bad answer) is [`Decision::NoAnswer`]: the turn runs out on
//! the match's clock.

use crate::bot::{Bot, Context, Decision};
use game::decide::DecideRequest;
use game::NoiseSecret;
use hosted::{BotModule, DecideError, DecisionSeed};
use std::sync::Arc;

/// What a hosted bot used over its decisions so far.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Usage {
    /// Decisions made.
    pub decisions: u64,
    /// Fuel used by the decisions made.
    pub fuel: u64,
    /// Shots simulated through the host.
    pub shots: u64,
    /// Decisions that failed, each with its error.
    pub failures: Vec<String>,
}

/// A WebAssembly bot in one match.
pub struct HostedBot {
    module: Arc<BotModule>,
    secret: NoiseSecret,
    usage: Usage,
}

impl HostedBot {
    /// `module` playing in the match whose noise secret is `secret`.
    pub fn new(module: Arc<BotModule>, secret: NoiseSecret) -> HostedBot {
        HostedBot {
            module,
            secret,
            usage: Usage::default(),
        }
    }

    /// What it used so far.
    pub fn usage(&self) -> &Usage {
        &self.usage
    }

    /// One decision, with its error.
    pub fn try_decide(&mut self, request: &DecideRequest) -> Result<Decision, DecideError> {
        let seed = DecisionSeed::derive(&self.secret, request);
        let decided = self.module.decide(request, seed)?;
        self.usage.decisions += 1;
        self.usage.fuel += decided.fuel;
        self.usage.shots += decided.shots;
        Ok(decided.decision.into())
    }
}

impl Bot for HostedBot {
    fn decide(&mut self, ctx: &Context) -> Decision {
        let request = DecideRequest {
            me: ctx.me,
            view: ctx.view.clone(),
        };
        match self.try_decide(&request) {
            Ok(d) => d,
            Err(e) => {
                self.usage.failures.push(e.to_string());
                Decision::NoAnswer
            }
        }
    }
}
