//! One decision of a hosted bot: a fresh instance of its module under the
//! decision's fuel and memory limits, the request written into its memory,
//! `chapaev_decide` called, the answer read back and checked. Whatever the
//! module does — loop, trap, exhaust its memory, answer nonsense — ends in
//! a [`DecideError`]; nothing outside the decision's store is touched.

use crate::abi;
use crate::host::HostState;
use crate::module::BotModule;
use crate::randomness::DecisionSeed;
use game::decide::{AnswerError, DecideRequest};
use game::session::BotDecision;
use wasmi::errors::ErrorKind;
use wasmi::{Store, StoreLimitsBuilder, TrapCode};

/// A decision made.
#[derive(Clone, Debug, PartialEq)]
pub struct Decided {
    /// What the bot decided.
    pub decision: BotDecision,
    /// Fuel it used, instantiation and simulated shots included.
    pub fuel: u64,
    /// Shots it simulated through the host.
    pub shots: u64,
}

/// Why a decision was not made. Under a match's rules every one of them
/// counts as the turn's clock running out.
#[derive(Debug, thiserror::Error)]
pub enum DecideError {
    #[error("the bot ran out of fuel ({fuel} units per decision)")]
    OutOfFuel { fuel: u64 },
    #[error("the bot went over its memory limit of {limit} bytes")]
    Memory {
        limit: usize,
        #[source]
        source: wasmi::Error,
    },
    #[error("the bot trapped: {code}")]
    Trap {
        code: TrapCode,
        #[source]
        source: wasmi::Error,
    },
    #[error("the bot could not be started: {0}")]
    Instantiate(#[source] wasmi::Error),
    #[error("the bot's answer lies outside its memory (at {ptr}, {len} bytes)")]
    AnswerOutOfBounds { ptr: u32, len: u32 },
    #[error("the bot's answer is {len} bytes, above the limit of {limit}")]
    AnswerTooLong { len: u32, limit: u32 },
    #[error("chapaev_alloc gave {ptr}, which cannot hold the {len}-byte request")]
    BadAlloc { ptr: i32, len: usize },
    #[error("the bot's answer is not a decision: {0}")]
    Answer(#[from] AnswerError),
}

impl BotModule {
    /// The bot's decision on `request`, its random stream keyed by `seed`.
    pub fn decide(
        &self,
        request: &DecideRequest,
        seed: DecisionSeed,
    ) -> Result<Decided, DecideError> {
        let limits = &self.limits;
        let state = HostState {
            limits: StoreLimitsBuilder::new()
                .memory_size(limits.max_memory_bytes)
                .memories(1)
                .tables(4)
                .table_elements(100_000)
                .instances(1)
                .trap_on_grow_failure(true)
                .build(),
            config: request.view.config.clone(),
            stream: seed.stream(),
            shot_fuel: limits.shot_fuel,
            max_shots: limits.max_shots_per_call,
            shots: 0,
        };
        let mut store = Store::new(&self.engine, state);
        store.limiter(|s| &mut s.limits);
        let budget = limits.fuel_per_decision;
        let classify = |e: wasmi::Error| -> DecideError {
            match e.as_trap_code() {
                Some(TrapCode::OutOfFuel) => DecideError::OutOfFuel { fuel: budget },
                Some(TrapCode::GrowthOperationLimited) => DecideError::Memory {
                    limit: limits.max_memory_bytes,
                    source: e,
                },
                Some(code) => DecideError::Trap { code, source: e },
                None => match e.kind() {
                    ErrorKind::Memory(_) | ErrorKind::Table(_) => DecideError::Memory {
                        limit: limits.max_memory_bytes,
                        source: e,
                    },
                    _ => DecideError::Instantiate(e),
                },
            }
        };
        // Fuel is set up with the store: a start function pays from it too.
        store.set_fuel(budget).map_err(classify)?;
        let instance = self
            .linker
            .instantiate_and_start(&mut store, &self.module)
            .map_err(classify)?;
        // The exports were checked at load; these lookups cannot miss.
        let memory = instance
            .get_memory(&store, abi::MEMORY)
            .ok_or_else(|| DecideError::Instantiate(wasmi::Error::new("no memory export")))?;
        let alloc = instance
            .get_typed_func::<i32, i32>(&store, abi::ALLOC)
            .map_err(DecideError::Instantiate)?;
        let decide = instance
            .get_typed_func::<(i32, i32), i64>(&store, abi::DECIDE)
            .map_err(DecideError::Instantiate)?;
        let text = request.to_json();
        let len = text.len();
        let bad_alloc = |ptr| DecideError::BadAlloc { ptr, len };
        let len32 = i32::try_from(len).map_err(|_| bad_alloc(-1))?;
        let ptr = alloc.call(&mut store, len32).map_err(classify)?;
        memory
            .write(&mut store, ptr as u32 as usize, text.as_bytes())
            .map_err(|_| bad_alloc(ptr))?;
        let packed = decide.call(&mut store, (ptr, len32)).map_err(classify)?;
        let (at, n) = abi::unpack(packed);
        if n > limits.max_answer_bytes {
            return Err(DecideError::AnswerTooLong {
                len: n,
                limit: limits.max_answer_bytes,
            });
        }
        let mut answer = vec![0u8; n as usize];
        memory
            .read(&store, at as usize, &mut answer)
            .map_err(|_| DecideError::AnswerOutOfBounds { ptr: at, len: n })?;
        let decision = request.answer(&answer)?;
        let left = store.get_fuel().unwrap_or(0);
        Ok(Decided {
            decision,
            fuel: budget - left,
            shots: store.data().shots,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Limits;
    use game::{Config, Game, Side};

    fn limits() -> Limits {
        Limits {
            fuel_per_decision: 20_000_000,
            max_memory_bytes: 4 << 20,
            ..Limits::default()
        }
    }

    fn request() -> DecideRequest {
        DecideRequest {
            me: Side::White,
            view: Game::new(Config::standard(), 1).unwrap().view(),
        }
    }

    fn seed(k: u8) -> DecisionSeed {
        DecisionSeed::from_bytes([k; 32])
    }

    /// A module whose `chapaev_decide` runs `body` (leaving an i64), with
    /// `answer` at address 0 of its memory.
    fn bot(imports: &str, memory: &str, answer: &str, body: &str) -> BotModule {
        let text = format!(
            r#"(module {imports}
                (memory (export "memory") {memory})
                (data (i32.const 0) "{answer}")
                (func (export "chapaev_alloc") (param i32) (result i32) i32.const 65536)
                (func (export "chapaev_decide") (param i32 i32) (result i64) {body}))"#,
            answer = answer.replace('"', "\\\"")
        );
        BotModule::load(&wat::parse_str(text).unwrap(), &limits()).unwrap()
    }

    const RESIGN: &str = r#"{"type":"resign"}"#;

    fn resigner() -> BotModule {
        bot("", "2", RESIGN, &format!("i64.const {}", RESIGN.len()))
    }

    #[test]
    fn a_well_behaved_module_decides_and_reports_its_fuel() {
        let d = resigner().decide(&request(), seed(1)).unwrap();
        assert_eq!(d.decision, BotDecision::Resign);
        assert!(d.fuel > 0 && d.fuel < 1000, "{}", d.fuel);
        assert_eq!(d.shots, 0);
    }

    #[test]
    fn an_infinite_loop_runs_out_of_fuel_and_the_next_decision_is_unharmed() {
        let looping = bot("", "2", RESIGN, "(loop br 0) i64.const 0");
        let err = looping.decide(&request(), seed(1)).unwrap_err();
        assert!(
            matches!(err, DecideError::OutOfFuel { fuel: 20_000_000 }),
            "{err}"
        );
        // The same module and another one both go on deciding.
        assert!(matches!(
            looping.decide(&request(), seed(2)),
            Err(DecideError::OutOfFuel { .. })
        ));
        assert!(resigner().decide(&request(), seed(1)).is_ok());
    }

    #[test]
    fn a_start_function_that_loops_pays_from_the_same_fuel() {
        let text = r#"(module
            (memory (export "memory") 1)
            (func $spin (loop br 0))
            (start $spin)
            (func (export "chapaev_alloc") (param i32) (result i32) i32.const 0)
            (func (export "chapaev_decide") (param i32 i32) (result i64) i64.const 0))"#;
        let m = BotModule::load(&wat::parse_str(text).unwrap(), &limits()).unwrap();
        assert!(matches!(
            m.decide(&request(), seed(1)),
            Err(DecideError::OutOfFuel { .. })
        ));
    }

    #[test]
    fn a_memory_bomb_is_stopped_at_the_memory_limit() {
        // Grows by 16 pages (1 MiB) until refused: the fourth grow passes 4 MiB.
        let growing = bot(
            "",
            "2",
            RESIGN,
            "(loop (drop (memory.grow (i32.const 16))) br 0) i64.const 0",
        );
        let err = growing.decide(&request(), seed(1)).unwrap_err();
        assert!(
            matches!(err, DecideError::Memory { limit, .. } if limit == 4 << 20),
            "{err}"
        );
    }

    #[test]
    fn a_trap_is_reported_with_its_code() {
        let trapping = bot("", "2", RESIGN, "unreachable");
        let err = trapping.decide(&request(), seed(1)).unwrap_err();
        assert!(
            matches!(
                err,
                DecideError::Trap {
                    code: TrapCode::UnreachableCodeReached,
                    ..
                }
            ),
            "{err}"
        );
        let dividing = bot(
            "",
            "2",
            RESIGN,
            "(drop (i32.div_u (i32.const 1) (i32.const 0))) i64.const 0",
        );
        assert!(matches!(
            dividing.decide(&request(), seed(1)),
            Err(DecideError::Trap {
                code: TrapCode::IntegerDivisionByZero,
                ..
            })
        ));
    }

    #[test]
    fn an_answer_outside_memory_too_long_or_not_a_decision_is_refused() {
        let outside = bot("", "2", RESIGN, "i64.const 0x7fff000000000010");
        assert!(matches!(
            outside.decide(&request(), seed(1)),
            Err(DecideError::AnswerOutOfBounds { .. })
        ));
        let long = bot("", "2", RESIGN, "i64.const 100000");
        assert!(matches!(
            long.decide(&request(), seed(1)),
            Err(DecideError::AnswerTooLong { .. })
        ));
        let chat = r#"{"type":"chat","text":"hi"}"#;
        let chatty = bot("", "2", chat, &format!("i64.const {}", chat.len()));
        assert!(matches!(
            chatty.decide(&request(), seed(1)),
            Err(DecideError::Answer(AnswerError::NotADecision("chat")))
        ));
        let alloc_outside = r#"(module
            (memory (export "memory") 1)
            (func (export "chapaev_alloc") (param i32) (result i32) i32.const -8)
            (func (export "chapaev_decide") (param i32 i32) (result i64) i64.const 0))"#;
        let m = BotModule::load(&wat::parse_str(alloc_outside).unwrap(), &limits()).unwrap();
        assert!(matches!(
            m.decide(&request(), seed(1)),
            Err(DecideError::BadAlloc { ptr: -8, .. })
        ));
    }

    #[test]
    fn the_random_import_follows_the_seed() {
        // Swaps when the low bit of the first draw is set: both answers
        // sit in memory, 36 bytes apart.
        let yes = r#"{"type":"pie-decision","swap":true} "#;
        let no = r#"{"type":"pie-decision","swap":false}"#;
        let m = bot(
            r#"(import "chapaev" "random" (func $random (result i64)))"#,
            "2",
            &format!("{yes}{no}"),
            "(if (result i64) (i64.eqz (i64.and (call $random) (i64.const 1)))
               (then (i64.const 0x0000002400000024))
               (else (i64.const 0x0000000000000023)))",
        );
        let answers: Vec<_> = (0..16)
            .map(|k| m.decide(&request(), seed(k)).unwrap().decision)
            .collect();
        assert!(answers.contains(&BotDecision::Pie { swap: true }));
        assert!(answers.contains(&BotDecision::Pie { swap: false }));
        for k in 0..16 {
            assert_eq!(
                m.decide(&request(), seed(k)).unwrap().decision,
                answers[usize::from(k)]
            );
        }
    }

    /// `bytes` as a WAT data string.
    fn escaped(bytes: &[u8]) -> String {
        bytes.iter().map(|b| format!("\\{b:02x}")).collect()
    }

    /// A module that simulates `count` copies of one shot on the match's
    /// board, then resigns; the board sits at 4096, the shots at 8192, the
    /// answer rows go to 65536.
    fn simulating(count: usize, limits: &Limits) -> BotModule {
        let req = request();
        let board = game::batch::positions(&req.view.board);
        let shot = [0.0, 0.0, 1.0, f64::NAN, f64::NAN];
        let board_bytes: Vec<u8> = board.iter().flat_map(|x| x.to_le_bytes()).collect();
        let shot_bytes: Vec<u8> = (0..count)
            .flat_map(|_| shot.iter().flat_map(|x| x.to_le_bytes()))
            .collect();
        let text = format!(
            r#"(module
                (import "chapaev" "simulate" (func $simulate (param i32 i32 i32 i32) (result i32)))
                (memory (export "memory") 8)
                (data (i32.const 0) "{resign}")
                (data (i32.const 4096) "{board}")
                (data (i32.const 8192) "{shots}")
                (global $status (mut i32) (i32.const 0))
                (func (export "chapaev_alloc") (param i32) (result i32) i32.const 131072)
                (func (export "chapaev_decide") (param i32 i32) (result i64)
                  (if (call $simulate (i32.const 4096) (i32.const 8192) (i32.const {count}) (i32.const 65536))
                    (then unreachable))
                  ;; the first row's status is 0.0: the shot was played
                  (if (f64.ne (f64.load (i32.const 65536)) (f64.const 0)) (then unreachable))
                  i64.const {len}))"#,
            resign = RESIGN.replace('"', "\\\""),
            board = escaped(&board_bytes),
            shots = escaped(&shot_bytes),
            len = RESIGN.len(),
        );
        BotModule::load(&wat::parse_str(text).unwrap(), limits).unwrap()
    }

    #[test]
    fn simulated_shots_are_played_natively_and_charged_their_fixed_price() {
        let d = simulating(3, &limits())
            .decide(&request(), seed(1))
            .unwrap();
        assert_eq!(d.shots, 3);
        assert!(d.fuel >= 3 * limits().shot_fuel, "{}", d.fuel);
        assert!(d.fuel < 3 * limits().shot_fuel + 1000, "{}", d.fuel);
        // Physics it cannot pay for is never played.
        let poor = Limits {
            fuel_per_decision: 2 * limits().shot_fuel,
            ..limits()
        };
        assert!(matches!(
            simulating(3, &poor).decide(&request(), seed(1)),
            Err(DecideError::OutOfFuel { .. })
        ));
    }
}
