//! The store's promises, checked on both backends: every test here runs
//! once on SQLite (in memory) and once on PostgreSQL (a fresh database on
//! a local server, `local_services::local_postgres`; skipped with a line
//! on stderr where the machine has no PostgreSQL, unless
//! `CHAPAEV_REQUIRE_POSTGRES` is set).
//! What only SQLite has (its log file, migrations from older files, read
//! connections) is tested in [`super::sqlite`].

use super::*;
use crate::accounts::AccountError;
use game::name::computer_account;
use game::name::AccountName;
use game::protocol::ErrorCode;
use game::token::SeatToken;
use game::{Game, MatchResult, PieceId, Seat, Shot, Side, WinReason};
use glam::DVec2;

/// A store under test, a way to run a plain SQL statement on it (the
/// same text on both backends) to set up what the API cannot, and (where
/// the database outlives the store) a way to open it again.
pub(super) struct Backend {
    store: Arc<dyn Store>,
    raw: Box<dyn Fn(&str)>,
    reopen: Option<Box<dyn Fn() -> Arc<dyn Store>>>,
}

fn sqlite() -> Option<Backend> {
    let store = Arc::new(SqliteStore::in_memory().unwrap());
    let conn = store.clone();
    Some(Backend {
        store,
        raw: Box::new(move |sql| {
            conn.lock().unwrap().execute_batch(sql).unwrap();
        }),
        // In memory: SQLite's reopening is tested on disk, in its module.
        reopen: None,
    })
}

fn postgres(test: &str) -> Option<Backend> {
    let url = local_services::local_postgres::shared_database(test)?;
    let store = Arc::new(PostgresStore::connect(&url).unwrap());
    let again = url.clone();
    Some(Backend {
        store,
        raw: Box::new(move |sql| {
            let mut c = ::postgres::Client::connect(&url, ::postgres::NoTls).unwrap();
            c.batch_execute(sql).unwrap();
        }),
        reopen: Some(Box::new(move || {
            Arc::new(PostgresStore::connect(&again).unwrap())
        })),
    })
}

/// PostgreSQL only (it restarts the database): the writer's connection
/// and the pool's idle one die with the database; the first move written
/// after it is back goes through all the same (its batch begins again on
/// a fresh connection instead of being refused), and reads get fresh
/// connections.
#[test]
fn on_postgres_the_first_move_after_the_database_restarts_is_written_not_refused() {
    let test = "store_postgres_restart";
    let mut pg = match local_services::LocalPostgres::start() {
        Ok(pg) => pg,
        Err(e) => {
            local_services::skip::without(
                test,
                local_services::skip::Service::Postgres,
                &e.to_string(),
            );
            return;
        }
    };
    let url = pg.fresh_database("restart").unwrap();
    let store = PostgresStore::connect(&url).unwrap();
    store.create(&stored("m1")).unwrap();
    let first = RecordedMove::Resign { side: Side::White };
    store.append_move("m1", 0, &first, &LIVE).unwrap();
    pg.start_again().unwrap();
    let second = RecordedMove::Resign { side: Side::Black };
    store
        .append_move("m1", 1, &second, &LIVE)
        .expect("the first move after the restart is written");
    assert_eq!(store.moves("m1").unwrap(), vec![first, second]);
}

/// Each named test, on each backend.
macro_rules! on_both_backends {
    ($($test:ident),* $(,)?) => {
        mod on_sqlite {
            $(#[test] fn $test() { super::$test(super::sqlite().unwrap()) })*
        }
        mod on_postgres {
            $(#[test] fn $test() {
                if let Some(b) = super::postgres(stringify!($test)) { super::$test(b) }
            })*
        }
    };
}

on_both_backends!(
    a_match_and_its_moves_come_back_as_a_replayable_record,
    a_match_begun_before_secrets_comes_back_keyed_by_its_seed,
    a_seeded_match_keeps_its_public_seed_and_shows_it_in_its_summary,
    moves_written_at_once_from_many_threads_all_land_and_a_bad_one_fails_alone,
    a_move_index_is_written_once_and_a_failed_move_changes_nothing,
    the_second_seat_is_taken_once_and_listing_filters_by_status,
    open_matches_left_alone_expire_and_live_ones_are_resumed_newest_first,
    the_store_survives_reopening,
    group_commits_are_counted_and_timed_in_the_metrics,
    a_new_account_starts_provisional_at_1500_and_its_key_proves_it,
    a_name_taken_in_any_case_is_refused_and_changes_nothing,
    a_wrong_or_revoked_key_proves_nothing,
    the_leaderboard_lists_one_kind_established_ratings_first,
    a_person_may_add_a_password_and_sign_in_with_it_for_a_new_key,
    an_account_inactive_for_the_stated_window_leaves_the_leaderboard,
    the_last_move_of_a_rated_match_moves_both_ratings_once,
    a_casual_match_or_a_seat_without_an_account_rates_nothing,
    the_computer_levels_have_bot_accounts_nobody_can_register,
    every_match_id_is_walked_in_pages_in_byte_order,
    module_versions_are_kept_by_hash_with_one_active_and_a_refused_change_writes_nothing,
    only_a_bots_account_uploads_a_module_and_one_the_runtime_refuses_is_not_stored,
    the_hosted_bots_are_the_bots_with_an_active_module_and_a_seat_keeps_its_version,
    a_version_an_unfinished_match_plays_with_is_kept_until_the_match_ends,
    a_hosted_bot_holds_one_ladder_claim_at_a_time_until_its_match_is_finished,
    of_ladder_claims_on_one_bot_made_at_once_from_many_connections_one_wins,
);

pub(super) fn stored(id: &str) -> StoredMatch {
    StoredMatch {
        id: id.into(),
        created_at: 0,
        config: Config::default(),
        noise: NoiseKey::from(u64::MAX - 1),
        physics: game::PHYSICS_VERSION,
        status: Status::Open,
        bot: None,
        turn_seconds: 60,
        seats: [
            StoredSeat {
                name: Some("Petka".into()),
                token: Some(TokenHash::of("t1")),
                account: None,
                module: None,
            },
            StoredSeat::default(),
        ],
        rematch_of: None,
        rated: false,
        seed: None,
    }
}

pub(super) const LIVE: AfterMove<'static> = AfterMove {
    status: Status::Live,
    shots: 0,
    result: None,
    winner: None,
};

fn a_match_and_its_moves_come_back_as_a_replayable_record(b: Backend) {
    let store = b.store;
    store.create(&stored("m1")).unwrap();
    store
        .seat_second("m1", "Anka", &TokenHash::of("t2"), None)
        .unwrap();
    let mut g = Game::new(Config::default(), u64::MAX - 1).unwrap();
    let piece = PieceId::new(Side::White, 4).unwrap();
    g.play(
        Side::White,
        Shot::new(piece, DVec2::new(0.0, 2.0), g.config()).unwrap(),
    )
    .unwrap();
    let after = AfterMove { shots: 1, ..LIVE };
    store
        .append_move("m1", 0, &g.record().moves[0], &after)
        .unwrap();
    let (m, record) = store.load("m1").unwrap().unwrap();
    assert_eq!(m.noise, NoiseKey::from(u64::MAX - 1));
    assert_eq!(m.status, Status::Live);
    assert_eq!(m.seats[1].token, Some(TokenHash::of("t2")));
    // The store keeps the secret, to resume the match from: the record it
    // gives back reveals it (the server publishes it only once over).
    assert_eq!(record, g.private_record());
    assert!(g.record().noise.as_ref().unwrap().secret.is_none());
    let replay = game::Replay::new(record).unwrap();
    assert_eq!(replay.game().view(), g.view());
    assert_eq!(store.live().unwrap(), vec!["m1".to_string()]);
}

fn a_match_begun_before_secrets_comes_back_keyed_by_its_seed(b: Backend) {
    let store = b.store;
    let mut old = stored("m0");
    old.noise = NoiseKey::SplitMix64(u64::MAX - 5);
    store.create(&old).unwrap();
    let (m, record) = store.load("m0").unwrap().unwrap();
    assert_eq!(m.noise, NoiseKey::SplitMix64(u64::MAX - 5));
    assert_eq!(record.seed, Some(u64::MAX - 5));
    assert_eq!(record.noise, None);
    assert_eq!(record.key(), Ok(NoiseKey::SplitMix64(u64::MAX - 5)));
}

fn a_seeded_match_keeps_its_public_seed_and_shows_it_in_its_summary(b: Backend) {
    let store = b.store;
    // The largest seed the API takes, and one past i64 (kept bit for bit).
    for (id, seed) in [("s1", (1u64 << 53) - 1), ("s2", u64::MAX - 7)] {
        let mut m = stored(id);
        m.noise = NoiseKey::from(seed);
        m.seed = Some(seed);
        store.create(&m).unwrap();
        let (back, _) = store.load(id).unwrap().unwrap();
        assert_eq!((back.seed, back.noise), (Some(seed), NoiseKey::from(seed)));
        assert_eq!(store.summary(id).unwrap().unwrap().seed, Some(seed));
    }
    store.create(&stored("s3")).unwrap();
    assert_eq!(store.load("s3").unwrap().unwrap().0.seed, None);
    assert_eq!(store.summary("s3").unwrap().unwrap().seed, None);
}

fn moves_written_at_once_from_many_threads_all_land_and_a_bad_one_fails_alone(b: Backend) {
    let store = b.store;
    let ids: Vec<String> = (0..6).map(|k| format!("m{k}")).collect();
    for id in &ids {
        store.create(&stored(id)).unwrap();
    }
    let threads: Vec<_> = ids
        .iter()
        .cloned()
        .chain(["nope".to_string()])
        .map(|id| {
            let store = store.clone();
            std::thread::spawn(move || {
                (0..40)
                    .map(|k| {
                        let after = AfterMove {
                            shots: k + 1,
                            ..LIVE
                        };
                        let pass = RecordedMove::Pass { side: Side::White };
                        store.append_move(&id, k as usize, &pass, &after).is_ok()
                    })
                    .collect::<Vec<bool>>()
            })
        })
        .collect();
    let results: Vec<Vec<bool>> = threads.into_iter().map(|t| t.join().unwrap()).collect();
    for (id, ok) in ids.iter().zip(&results) {
        assert!(ok.iter().all(|&b| b), "{id}: every move is acknowledged");
        assert_eq!(
            store.moves(id).unwrap().len(),
            40,
            "{id}: every move is stored"
        );
        assert_eq!(store.summary(id).unwrap().unwrap().shots, 40);
    }
    assert!(
        results[6].iter().all(|&b| !b),
        "moves of an unknown match fail"
    );
    assert!(store.moves("nope").unwrap().is_empty());
}

fn a_move_index_is_written_once_and_a_failed_move_changes_nothing(b: Backend) {
    let store = b.store;
    store.create(&stored("m1")).unwrap();
    let resign = RecordedMove::Resign { side: Side::White };
    store.append_move("m1", 0, &resign, &LIVE).unwrap();
    assert!(store.append_move("m1", 0, &resign, &LIVE).is_err());
    // An unknown match: the move insert fails on the foreign key, nothing is written.
    assert!(store.append_move("nope", 0, &resign, &LIVE).is_err());
    assert!(store.moves("nope").unwrap().is_empty());
    assert_eq!(store.moves("m1").unwrap(), vec![resign]);
}

fn every_match_id_is_walked_in_pages_in_byte_order(b: Backend) {
    let store = b.store;
    for id in ["b", "a", "C", "a2", "a10"] {
        store.create(&stored(id)).unwrap();
    }
    let mut walked = Vec::new();
    let mut after: Option<String> = None;
    loop {
        let page = store.match_ids(after.as_deref(), 2).unwrap();
        assert!(page.len() <= 2);
        let Some(last) = page.last().cloned() else {
            break;
        };
        walked.extend(page);
        after = Some(last);
    }
    assert_eq!(walked, ["C", "a", "a10", "a2", "b"]);
}

fn the_second_seat_is_taken_once_and_listing_filters_by_status(b: Backend) {
    let store = b.store;
    store.create(&stored("a")).unwrap();
    store.create(&stored("b")).unwrap();
    store
        .seat_second("a", "x", &TokenHash::of("t"), None)
        .unwrap();
    assert!(store
        .seat_second("a", "y", &TokenHash::of("u"), None)
        .is_err());
    let open = store.list(Some(Status::Open), 10).unwrap();
    assert_eq!(open.len(), 1);
    assert_eq!(open[0].match_id, "b");
    assert_eq!(store.list(None, 10).unwrap().len(), 2);
    assert_eq!(
        store.summary("a").unwrap().unwrap().second.as_deref(),
        Some("x")
    );
    assert!(store.summary("zz").unwrap().is_none());
}

fn open_matches_left_alone_expire_and_live_ones_are_resumed_newest_first(b: Backend) {
    let store = b.store;
    for id in ["old-open", "waited-for", "live-a", "live-b", "new-open"] {
        store.create(&stored(id)).unwrap();
    }
    for id in ["live-a", "live-b"] {
        store
            .seat_second(id, "Anka", &TokenHash::of("t2"), None)
            .unwrap();
    }
    for (id, at) in [
        ("old-open", 0),
        ("waited-for", 0),
        ("live-a", 5),
        ("live-b", 9),
    ] {
        (b.raw)(&format!(
            "UPDATE matches SET updated_at = {at} WHERE id = '{id}'"
        ));
    }
    let expired = store
        .expire_open(3600, &|id: &str| id == "waited-for")
        .unwrap();
    assert_eq!(expired, ["old-open"]);
    assert!(store.get("old-open").unwrap().is_none());
    for kept in ["waited-for", "new-open", "live-a"] {
        assert!(store.get(kept).unwrap().is_some(), "{kept}");
    }
    // Live matches, however old, never expire, and resume newest first.
    assert_eq!(store.live().unwrap(), ["live-b", "live-a"]);
}

fn the_store_survives_reopening(b: Backend) {
    b.store.create(&stored("m")).unwrap();
    let (_, key) = b
        .store
        .create_account(&AccountName::parse("Anka").unwrap(), false)
        .unwrap();
    b.store
        .append_move("m", 0, &RecordedMove::Pass { side: Side::White }, &LIVE)
        .unwrap();
    // A second store on the same database (as a restarted server, or
    // another node) sees everything, and migrating again changes nothing.
    let Some(reopen) = b.reopen else {
        return;
    };
    let again = reopen();
    assert_eq!(
        again.get("m").unwrap().unwrap().seats[0].name.as_deref(),
        Some("Petka")
    );
    assert_eq!(again.moves("m").unwrap().len(), 1);
    assert_eq!(again.account_of_key(&key).unwrap().name, "Anka");
}

fn group_commits_are_counted_and_timed_in_the_metrics(b: Backend) {
    let store = b.store;
    store.create(&stored("m")).unwrap();
    for k in 0..3 {
        let pass = RecordedMove::Pass { side: Side::White };
        store.append_move("m", k, &pass, &LIVE).unwrap();
    }
    let mut text = String::new();
    store.render_metrics(&mut text);
    assert!(
        text.contains("chapaev_store_moves_committed_total 3\n"),
        "{text}"
    );
    // Each append waited for its own commit.
    assert!(
        text.contains("chapaev_store_commit_seconds_count 3\n"),
        "{text}"
    );
    assert!(text.contains("chapaev_store_commit_seconds_bucket{le=\"+Inf\"} 3\n"));
}

fn name(s: &str) -> AccountName {
    AccountName::parse(s).unwrap()
}

fn code(e: AccountError) -> ErrorCode {
    match e {
        AccountError::Refused(r) => r.code,
        other => panic!("not a refusal: {other}"),
    }
}

fn a_new_account_starts_provisional_at_1500_and_its_key_proves_it(b: Backend) {
    let store = b.store;
    let (profile, key) = store.create_account(&name("Anka"), false).unwrap();
    assert_eq!(
        (profile.rating, profile.deviation, profile.provisional),
        (1500, 500, true)
    );
    assert_eq!(store.account_of_key(&key).unwrap().name, "Anka");
    assert_eq!(store.account("anka").unwrap().unwrap().name, "Anka");
    assert!(store.account("Petka").unwrap().is_none());
}

fn a_name_taken_in_any_case_is_refused_and_changes_nothing(b: Backend) {
    let store = b.store;
    let (_, key) = store.create_account(&name("Anka"), false).unwrap();
    let err = store.create_account(&name("ANKA"), true).unwrap_err();
    assert_eq!(code(err), ErrorCode::NameTaken);
    let anka = store.account_of_key(&key).unwrap();
    assert!(!anka.bot);
    assert!(store
        .leaderboard(true, 10)
        .unwrap()
        .iter()
        .all(|p| p.name.starts_with(game::name::COMPUTER_PREFIX)));
}

fn a_wrong_or_revoked_key_proves_nothing(b: Backend) {
    let store = b.store;
    let (_, key) = store.create_account(&name("Furmanov"), true).unwrap();
    let wrong = SeatToken::new("0".repeat(32));
    assert_eq!(
        code(store.account_of_key(&wrong).unwrap_err()),
        ErrorCode::BadKey
    );
    let (_, second) = store.add_key(&key).unwrap();
    store.revoke_key(&key).unwrap();
    assert_eq!(
        code(store.account_of_key(&key).unwrap_err()),
        ErrorCode::BadKey
    );
    assert_eq!(code(store.revoke_key(&key).unwrap_err()), ErrorCode::BadKey);
    assert_eq!(store.account_of_key(&second).unwrap().name, "Furmanov");
}

fn the_leaderboard_lists_one_kind_established_ratings_first(b: Backend) {
    let store = b.store;
    for (n, bot) in [("greedy", true), ("search", true), ("Anka", false)] {
        store.create_account(&name(n), bot).unwrap();
    }
    (b.raw)("UPDATE accounts SET rating = 1620, deviation = 80 WHERE name = 'search'");
    (b.raw)("UPDATE accounts SET rating = 1700 WHERE name = 'greedy'");
    let bots: Vec<(String, bool)> = store
        .leaderboard(true, 10)
        .unwrap()
        .into_iter()
        .filter(|p| !p.name.starts_with(game::name::COMPUTER_PREFIX))
        .map(|p| (p.name, p.provisional))
        .collect();
    assert_eq!(
        bots,
        [("search".to_string(), false), ("greedy".to_string(), true)]
    );
    assert_eq!(store.leaderboard(false, 10).unwrap().len(), 1);
}

fn an_account_inactive_for_the_stated_window_leaves_the_leaderboard(b: Backend) {
    let store = b.store;
    for n in ["Anka", "Petka"] {
        store.create_account(&name(n), false).unwrap();
    }
    let listed = || -> Vec<String> {
        let board = store.leaderboard(false, 10).unwrap();
        board.into_iter().map(|p| p.name).collect()
    };
    assert_eq!(listed(), ["Anka", "Petka"]);
    // Made a day longer ago than the window, never rated since.
    let old = now() - (super::LEADERBOARD_ACTIVE_DAYS + 1) * 24 * 3600;
    (b.raw)(&format!(
        "UPDATE accounts SET created_at = {old} WHERE name = 'Petka'"
    ));
    assert_eq!(listed(), ["Anka"]);
    // Still an account: its page and its key work.
    assert!(store.account("Petka").unwrap().is_some());
}

fn a_person_may_add_a_password_and_sign_in_with_it_for_a_new_key(b: Backend) {
    let store = b.store;
    let (_, key) = store.create_account(&name("Anka"), false).unwrap();
    let short = store.set_password(&key, "short").unwrap_err();
    assert_eq!(code(short), ErrorCode::BadPassword);
    store.set_password(&key, "machine-gun cart").unwrap();
    let (_, stored) = store.password("ANKA").unwrap().unwrap();
    assert!(stored.starts_with("$argon2id$") && !stored.contains("machine-gun"));
    let (profile, new_key) = store.sign_in("anka", "machine-gun cart").unwrap();
    assert_eq!(profile.name, "Anka");
    assert_eq!(store.account_of_key(&new_key).unwrap().name, "Anka");
    for (who, password) in [("Anka", "machine-gun car"), ("Petka", "machine-gun cart")] {
        let e = store.sign_in(who, password).unwrap_err();
        assert_eq!(code(e), ErrorCode::BadPassword, "{who}");
    }
    let (_, bot) = store.create_account(&name("Furmanov"), true).unwrap();
    let e = store.set_password(&bot, "machine-gun cart").unwrap_err();
    assert_eq!(code(e), ErrorCode::BadMessage);
}

fn rated(id: &str, accounts: [&str; 2]) -> StoredMatch {
    StoredMatch {
        status: Status::Live,
        seats: accounts.map(|a| StoredSeat {
            name: Some(a.into()),
            token: None,
            account: Some(a.into()),
            module: None,
        }),
        rated: true,
        ..stored(id)
    }
}

fn resign_first(store: &dyn Store, id: &str, index: usize) -> Result<(), StoreError> {
    let result = MatchResult::Won {
        side: Side::Black,
        reason: WinReason::Resignation,
    };
    store.append_move(
        id,
        index,
        &RecordedMove::Resign { side: Side::White },
        &AfterMove {
            status: Status::Finished,
            shots: 0,
            result: Some(&result),
            winner: Some(Seat::Second),
        },
    )
}

fn account(store: &dyn Store, name: &str) -> crate::store::Profile {
    store.account(name).unwrap().unwrap()
}

fn the_last_move_of_a_rated_match_moves_both_ratings_once(b: Backend) {
    let store = &*b.store;
    for n in ["Anka", "Petka"] {
        store.create_account(&name(n), false).unwrap();
    }
    store.create(&rated("m1", ["Anka", "Petka"])).unwrap();
    resign_first(store, "m1", 0).unwrap();
    let (anka, petka) = (account(store, "Anka"), account(store, "Petka"));
    assert!(
        anka.rating < 1500 && petka.rating > 1500,
        "{anka:?} {petka:?}"
    );
    assert_eq!(anka.rating + petka.rating, 3000, "equals exchange points");
    assert_eq!((anka.games, petka.games), (1, 1));
    // The same last move again is refused (its index is taken) and
    // rates nothing.
    assert!(resign_first(store, "m1", 0).is_err());
    assert_eq!(account(store, "Anka"), anka);
    let history = store.rating_history("anka", 10).unwrap();
    assert_eq!(history.len(), 1);
    assert_eq!(
        (history[0].match_id.as_str(), history[0].rating),
        ("m1", anka.rating)
    );
    let played = store.matches_of("PETKA", 10).unwrap();
    assert_eq!(played.len(), 1);
    assert!(played[0].rated);
    assert_eq!(played[0].second_rating.unwrap().rating, petka.rating);
}

fn a_casual_match_or_a_seat_without_an_account_rates_nothing(b: Backend) {
    let store = &*b.store;
    for n in ["Anka", "Petka"] {
        store.create_account(&name(n), false).unwrap();
    }
    let mut casual = rated("m1", ["Anka", "Petka"]);
    casual.rated = false;
    store.create(&casual).unwrap();
    resign_first(store, "m1", 0).unwrap();
    let mut anonymous = rated("m2", ["Anka", "Petka"]);
    anonymous.seats[1].account = None;
    store.create(&anonymous).unwrap();
    resign_first(store, "m2", 0).unwrap();
    for n in ["Anka", "Petka"] {
        let a = account(store, n);
        assert_eq!((a.rating, a.games), (1500, 0), "{n}");
    }
    assert!(store.rating_history("Anka", 10).unwrap().is_empty());
}

fn the_computer_levels_have_bot_accounts_nobody_can_register(b: Backend) {
    for level in bots::Level::ALL {
        let a = account(&*b.store, &computer_account(level));
        assert!(a.bot);
        assert_eq!(a.rating, 1500);
    }
    let taken = AccountName::parse("Computer-Hard").unwrap_err();
    assert_eq!(taken, game::name::NameError::Reserved);
}

/// 64 hex digits naming a made-up version.
fn hash(k: u8) -> String {
    format!("{k:02x}").repeat(32)
}

fn module_versions_are_kept_by_hash_with_one_active_and_a_refused_change_writes_nothing(
    b: Backend,
) {
    let store = b.store;
    store.create_account(&name("Furmanov"), true).unwrap();
    store.create_account(&name("Anka"), true).unwrap();
    let new = |k: u8, bytes: &[u8], max| store.insert_module("Furmanov", &hash(k), bytes, max);
    let ModuleStored::New(first) = new(1, b"one", 3).unwrap() else {
        panic!("a new version")
    };
    assert_eq!((first.size, first.active), (3, true));
    assert!(matches!(new(2, b"two!", 3).unwrap(), ModuleStored::New(_)));
    let listed = |account: &str| -> Vec<(String, bool)> {
        store
            .modules(account)
            .unwrap()
            .into_iter()
            .map(|v| (v.hash, v.active))
            .collect()
    };
    assert_eq!(listed("Furmanov"), [(hash(2), true), (hash(1), false)]);
    // The same bytes again: the version it was, its upload time kept, active.
    let ModuleStored::Existing(again) = new(1, b"one", 3).unwrap() else {
        panic!("an existing version")
    };
    assert_eq!(again, first);
    assert_eq!(listed("furmanov"), [(hash(2), false), (hash(1), true)]);
    assert!(matches!(new(3, b"three", 3).unwrap(), ModuleStored::New(_)));
    // A fourth past a limit of three: nothing written, nothing made active.
    assert_eq!(
        new(4, b"four", 3).unwrap(),
        ModuleStored::TooMany { limit: 3 }
    );
    let before = listed("Furmanov");
    assert_eq!(before.len(), 3);
    assert_eq!(before[0], (hash(3), true));
    // Any version made active again; its bytes are what plays.
    let made = store
        .activate_module("FURMANOV", &hash(2))
        .unwrap()
        .unwrap();
    assert_eq!(
        (made.hash.as_str(), made.size, made.active),
        (hash(2).as_str(), 4, true)
    );
    let (active, bytes) = store.active_module("Furmanov").unwrap().unwrap();
    assert_eq!((active.hash, bytes), (hash(2), b"two!".to_vec()));
    // A version the account lacks (another's, or none at all) changes nothing.
    let after = listed("Furmanov");
    assert_eq!(store.activate_module("Furmanov", &hash(9)).unwrap(), None);
    assert_eq!(store.activate_module("Anka", &hash(2)).unwrap(), None);
    assert_eq!(listed("Furmanov"), after);
    assert!(listed("Anka").is_empty());
    assert_eq!(store.active_module("Anka").unwrap(), None);
    // The active version stays; another is deleted, which frees its place.
    assert_eq!(
        store.delete_module("Furmanov", &hash(2)).unwrap(),
        ModuleDeleted::Active
    );
    assert_eq!(
        store.delete_module("Anka", &hash(1)).unwrap(),
        ModuleDeleted::Missing
    );
    assert_eq!(listed("Furmanov"), after);
    assert_eq!(
        store.delete_module("furmanov", &hash(1)).unwrap(),
        ModuleDeleted::Deleted
    );
    assert_eq!(listed("Furmanov"), [(hash(3), false), (hash(2), true)]);
    assert!(matches!(new(4, b"four", 3).unwrap(), ModuleStored::New(_)));
}

/// A module the runtime loads, answering `{"type":"resign"}` (`k` makes
/// each one's bytes, so its hash, its own).
fn resigning_module(k: u32) -> Vec<u8> {
    wat::parse_str(format!(
        r#"(module
            (memory (export "memory") 1)
            (data (i32.const 0) "{{\"type\":\"resign\"}}")
            (global i32 (i32.const {k}))
            (func (export "chapaev_alloc") (param i32) (result i32) i32.const 1024)
            (func (export "chapaev_decide") (param i32 i32) (result i64) i64.const 17))"#
    ))
    .unwrap()
}

fn only_a_bots_account_uploads_a_module_and_one_the_runtime_refuses_is_not_stored(b: Backend) {
    let store = b.store;
    let (person, _) = store.create_account(&name("Anka"), false).unwrap();
    let (bot, _) = store.create_account(&name("Furmanov"), true).unwrap();
    let good = resigning_module(1);
    assert_eq!(
        code(store.upload_module(&person, &good).unwrap_err()),
        ErrorCode::NotABot
    );
    assert!(store.modules("Anka").unwrap().is_empty());
    let wasi = wat::parse_str(
        r#"(module
            (import "wasi_snapshot_preview1" "fd_write" (func (param i32 i32 i32 i32) (result i32)))
            (memory (export "memory") 1)
            (func (export "chapaev_alloc") (param i32) (result i32) i32.const 0)
            (func (export "chapaev_decide") (param i32 i32) (result i64) i64.const 0))"#,
    )
    .unwrap();
    let no_decide = wat::parse_str(r#"(module (memory (export "memory") 1))"#).unwrap();
    for bad in [&b"not webassembly"[..], &wasi, &no_decide] {
        assert_eq!(
            code(store.upload_module(&bot, bad).unwrap_err()),
            ErrorCode::BadModule
        );
    }
    assert!(store.modules("Furmanov").unwrap().is_empty());
    let (new, version) = store.upload_module(&bot, &good).unwrap();
    let expected = hosted::BotModule::load(&good, &crate::accounts::modules::limits()).unwrap();
    assert!(new);
    assert_eq!(version.hash, expected.hash_hex());
    assert_eq!(version.size, good.len() as u64);
    assert!(
        !store.upload_module(&bot, &good).unwrap().0,
        "the same bytes again"
    );
    assert_eq!(
        code(store.activate_version(&bot, "not a hash").unwrap_err()),
        ErrorCode::NoSuchVersion
    );
    assert_eq!(
        store
            .activate_version(&bot, &version.hash.to_uppercase())
            .unwrap(),
        version
    );
}

fn the_hosted_bots_are_the_bots_with_an_active_module_and_a_seat_keeps_its_version(b: Backend) {
    let store = b.store;
    store.create_account(&name("Furmanov"), true).unwrap();
    store.create_account(&name("Anka"), true).unwrap();
    assert!(store.hosted_bots(10).unwrap().is_empty());
    store
        .insert_module("Furmanov", &hash(1), b"one", 3)
        .unwrap();
    store
        .insert_module("Furmanov", &hash(2), b"two", 3)
        .unwrap();
    let hosted: Vec<String> = store
        .hosted_bots(10)
        .unwrap()
        .into_iter()
        .map(|p| p.name)
        .collect();
    assert_eq!(hosted, ["Furmanov"], "Anka has no module");
    // Any version's bytes, active or not; none of another account's.
    assert_eq!(
        store.module_bytes("furmanov", &hash(1)).unwrap(),
        Some(b"one".to_vec())
    );
    assert_eq!(store.module_bytes("Anka", &hash(1)).unwrap(), None);
    // A hosted seat's version comes back with the match and its record.
    let mut m = stored("0123456789abcdef");
    m.seats[1] = StoredSeat {
        name: Some("Furmanov".into()),
        token: None,
        account: Some("Furmanov".into()),
        module: Some(hash(1)),
    };
    m.noise = NoiseKey::ChaCha20(game::NoiseSecret::from_hex(&hash(7)).unwrap());
    store.create(&m).unwrap();
    let got = store.get(&m.id).unwrap().unwrap();
    assert_eq!(got.seats[1].module, Some(hash(1)));
    assert_eq!(got.seats[0].module, None);
    let (_, record) = store.load(&m.id).unwrap().unwrap();
    assert_eq!(record.hosted, Some([None, Some(hash(1))]));
    let (_, plain) = store.load(&stored_plain(&*store)).unwrap().unwrap();
    assert_eq!(plain.hosted, None, "absent when no module played");
}

/// Stores a match no module plays; its id.
fn stored_plain(store: &dyn Store) -> String {
    let m = stored("00000000000000aa");
    store.create(&m).unwrap();
    m.id
}

/// A live match whose second seat `bot` plays with its version `version`.
fn hosted_match(id: &str, bot: &str, version: &str) -> StoredMatch {
    let mut m = stored(id);
    m.status = Status::Live;
    m.seats[1] = StoredSeat {
        name: Some(bot.into()),
        token: None,
        account: Some(bot.into()),
        module: Some(version.into()),
    };
    m.noise = NoiseKey::ChaCha20(game::NoiseSecret::from_hex(&hash(7)).unwrap());
    m
}

fn a_version_an_unfinished_match_plays_with_is_kept_until_the_match_ends(b: Backend) {
    let store = b.store;
    let (bot, _) = store.create_account(&name("Furmanov"), true).unwrap();
    store
        .insert_module("Furmanov", &hash(1), b"one", 3)
        .unwrap();
    let m = hosted_match("m1", "Furmanov", &hash(1));
    assert_eq!(
        store.create_hosted(&m, false).unwrap(),
        HostedCreated::Created
    );
    store
        .insert_module("Furmanov", &hash(2), b"two", 3)
        .unwrap();
    // Not active any more, but m1 (which a restart resumes with it) is
    // not over: kept, with a code that says why.
    assert_eq!(
        store.delete_module("furmanov", &hash(1)).unwrap(),
        ModuleDeleted::InUse
    );
    let refused = store.delete_version(&bot, &hash(1)).unwrap_err();
    assert_eq!(code(refused), ErrorCode::ModuleInUse);
    assert_eq!(
        store.module_bytes("Furmanov", &hash(1)).unwrap(),
        Some(b"one".to_vec())
    );
    // Over: it may go; a match paired with it since then is refused, and
    // nothing of that match is stored.
    resign_first(&*store, "m1", 0).unwrap();
    store.delete_version(&bot, &hash(1)).unwrap();
    assert_eq!(store.module_bytes("Furmanov", &hash(1)).unwrap(), None);
    let late = hosted_match("m2", "Furmanov", &hash(1));
    assert_eq!(
        store.create_hosted(&late, true).unwrap(),
        HostedCreated::NoVersion("Furmanov".into())
    );
    assert_eq!(store.get("m2").unwrap(), None);
}

fn a_hosted_bot_holds_one_ladder_claim_at_a_time_until_its_match_is_finished(b: Backend) {
    let store = b.store;
    store.create_account(&name("Furmanov"), true).unwrap();
    store
        .insert_module("Furmanov", &hash(1), b"one", 3)
        .unwrap();
    assert!(store.hosted_seats(10).unwrap().is_empty());
    let ladder = |id: &str| store.create_hosted(&hosted_match(id, "Furmanov", &hash(1)), true);
    assert_eq!(ladder("m1").unwrap(), HostedCreated::Created);
    // A second ladder match (another node's pairing, or one after a
    // restart) while m1 is not over: refused, nothing stored.
    let mut other = hosted_match("m2", "FURMANOV", &hash(1));
    other.seats[1].account = Some("FURMANOV".into());
    assert_eq!(
        store.create_hosted(&other, true).unwrap(),
        HostedCreated::Busy("FURMANOV".into())
    );
    assert_eq!(store.get("m2").unwrap(), None);
    // A challenge is no ladder match: it plays beside.
    let challenge = hosted_match("m3", "Furmanov", &hash(1));
    assert_eq!(
        store.create_hosted(&challenge, false).unwrap(),
        HostedCreated::Created
    );
    assert_eq!(store.hosted_seats(10).unwrap(), ["Furmanov", "Furmanov"]);
    // m1 over: the next ladder match is the bot's.
    resign_first(&*store, "m1", 0).unwrap();
    assert_eq!(ladder("m4").unwrap(), HostedCreated::Created);
    assert_eq!(
        ladder("m5").unwrap(),
        HostedCreated::Busy("Furmanov".into())
    );
    resign_first(&*store, "m3", 0).unwrap();
    resign_first(&*store, "m4", 0).unwrap();
    assert!(store.hosted_seats(10).unwrap().is_empty());
}

/// What several nodes do when each pairs the same bot in the same
/// instant: every claim on its own connection, at once.
fn of_ladder_claims_on_one_bot_made_at_once_from_many_connections_one_wins(b: Backend) {
    let store = b.store;
    store.create_account(&name("Furmanov"), true).unwrap();
    store
        .insert_module("Furmanov", &hash(1), b"one", 3)
        .unwrap();
    for round in 0..3 {
        let start = Arc::new(std::sync::Barrier::new(8));
        let claims: Vec<_> = (0..8)
            .map(|k| {
                let (store, start) = (store.clone(), start.clone());
                std::thread::spawn(move || {
                    let m = hosted_match(&format!("r{round}m{k}"), "Furmanov", &hash(1));
                    start.wait();
                    (m.id.clone(), store.create_hosted(&m, true).unwrap())
                })
            })
            .collect();
        let results: Vec<(String, HostedCreated)> =
            claims.into_iter().map(|t| t.join().unwrap()).collect();
        let won: Vec<&String> = results
            .iter()
            .filter(|(_, r)| *r == HostedCreated::Created)
            .map(|(id, _)| id)
            .collect();
        assert_eq!(won.len(), 1, "round {round}: {results:?}");
        for (id, r) in &results {
            if r != &HostedCreated::Created {
                assert_eq!(r, &HostedCreated::Busy("Furmanov".into()));
                assert_eq!(store.get(id).unwrap(), None, "{id} was not stored");
            }
        }
        assert_eq!(store.hosted_seats(10).unwrap(), ["Furmanov"]);
        resign_first(&*store, won[0], 0).unwrap();
    }
}
