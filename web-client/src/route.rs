//! Where the app is: the screens as addresses in the page's `#` fragment,
//! so a link opens a match, a replay, the sandbox, the leaderboard or a
//! player's page directly, and the browser's address always says where
//! the player is.

/// One screen of the app and what it shows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Route {
    /// Create, join, watch or replay matches.
    Lobby,
    /// Waiting to be paired with a stranger (rated or casual).
    QuickMatch { rated: bool },
    /// Play a match with the seat token this browser holds for it.
    Play { match_id: String },
    /// Take the empty seat of a match (a shared link), then play it.
    Join { match_id: String },
    /// Watch a live match.
    Watch { match_id: String },
    /// Replay a finished match.
    Replay { match_id: String },
    /// The offline physics sandbox.
    Sandbox,
    /// A match against a computer level played in this page, without the
    /// server (casual, never rated; a new one each time it opens).
    Offline { level: bots::Level },
    /// Signing in (create an account or paste a key), or the signed-in
    /// account's key and sign-out.
    SignIn,
    /// The best rated people (or bots).
    Leaderboard { bots: bool },
    /// An account's page: profile, rating over time, matches.
    Account { name: String },
}

/// Whether `id` looks like a match id (hex, as the server makes them).
pub(crate) fn valid_id(id: &str) -> bool {
    !id.is_empty() && id.len() <= 64 && id.chars().all(|c| c.is_ascii_alphanumeric())
}

impl Route {
    /// Reads a page address (or just its fragment); anything unknown is
    /// the lobby.
    pub fn parse(address: &str) -> Route {
        let frag = address.split_once('#').map_or("", |(_, f)| f);
        let parts: Vec<&str> = frag.trim_start_matches('/').split('/').collect();
        match parts.as_slice() {
            ["sandbox"] => Route::Sandbox,
            ["quick"] => Route::QuickMatch { rated: false },
            ["quick", "rated"] => Route::QuickMatch { rated: true },
            ["offline", level] => match bots::Level::parse(level) {
                Some(level) => Route::Offline { level },
                None => Route::Lobby,
            },
            ["account"] => Route::SignIn,
            ["leaderboard"] => Route::Leaderboard { bots: false },
            ["leaderboard", "bots"] => Route::Leaderboard { bots: true },
            ["player", name] if crate::account::valid_name(name) => Route::Account {
                name: name.to_string(),
            },
            [kind, id] if valid_id(id) => {
                let match_id = id.to_string();
                match *kind {
                    "play" => Route::Play { match_id },
                    "join" => Route::Join { match_id },
                    "watch" => Route::Watch { match_id },
                    "replay" => Route::Replay { match_id },
                    _ => Route::Lobby,
                }
            }
            _ => Route::Lobby,
        }
    }

    /// The fragment for this route (`#/...`).
    pub fn hash(&self) -> String {
        match self {
            Route::Lobby => "#/".to_string(),
            Route::QuickMatch { rated: false } => "#/quick".to_string(),
            Route::QuickMatch { rated: true } => "#/quick/rated".to_string(),
            Route::Play { match_id } => format!("#/play/{match_id}"),
            Route::Join { match_id } => format!("#/join/{match_id}"),
            Route::Watch { match_id } => format!("#/watch/{match_id}"),
            Route::Replay { match_id } => format!("#/replay/{match_id}"),
            Route::Sandbox => "#/sandbox".to_string(),
            Route::Offline { level } => format!("#/offline/{level}"),
            Route::SignIn => "#/account".to_string(),
            Route::Leaderboard { bots: false } => "#/leaderboard".to_string(),
            Route::Leaderboard { bots: true } => "#/leaderboard/bots".to_string(),
            Route::Account { name } => format!("#/player/{name}"),
        }
    }
}

/// The page's origin (`http://host:port`) from its full address.
pub fn origin(address: &str) -> String {
    let no_frag = address.split('#').next().unwrap_or("");
    match no_frag.find("://") {
        Some(i) => {
            let rest = &no_frag[i + 3..];
            let host = rest.split('/').next().unwrap_or("");
            format!("{}://{}", &no_frag[..i], host)
        }
        None => String::new(),
    }
}

/// The WebSocket origin matching an HTTP origin (`http` → `ws`, `https` → `wss`).
pub fn ws_origin(http_origin: &str) -> String {
    if let Some(rest) = http_origin.strip_prefix("https://") {
        format!("wss://{rest}")
    } else if let Some(rest) = http_origin.strip_prefix("http://") {
        format!("ws://{rest}")
    } else {
        http_origin.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_route_survives_its_own_address() {
        let id = "ab250fa2c87606f4".to_string();
        for r in [
            Route::Lobby,
            Route::QuickMatch { rated: false },
            Route::QuickMatch { rated: true },
            Route::Play {
                match_id: id.clone(),
            },
            Route::Join {
                match_id: id.clone(),
            },
            Route::Watch {
                match_id: id.clone(),
            },
            Route::Replay { match_id: id },
            Route::Sandbox,
            Route::Offline {
                level: bots::Level::Hard,
            },
            Route::Offline {
                level: bots::Level::Adaptive,
            },
            Route::SignIn,
            Route::Leaderboard { bots: false },
            Route::Leaderboard { bots: true },
            Route::Account {
                name: "Petka_2".into(),
            },
        ] {
            let addr = format!("http://127.0.0.1:8080/{}", r.hash());
            assert_eq!(Route::parse(&addr), r);
        }
    }

    #[test]
    fn unknown_or_hostile_addresses_open_the_lobby() {
        for a in [
            "http://h/",
            "http://h/#/nope/12",
            "http://h/#/play/",
            "http://h/#/play/a%20b",
            "#/play/<x>",
            "#/player/a%20b",
            "#/player/x",
            "#/offline/grandmaster",
            "#/offline/",
        ] {
            assert_eq!(Route::parse(a), Route::Lobby, "{a}");
        }
    }

    #[test]
    fn origins_follow_the_page_scheme() {
        assert_eq!(
            origin("http://127.0.0.1:8080/#/play/ab"),
            "http://127.0.0.1:8080"
        );
        assert_eq!(
            origin("https://chapaev.example/x/y?z#/"),
            "https://chapaev.example"
        );
        assert_eq!(ws_origin("http://127.0.0.1:8080"), "ws://127.0.0.1:8080");
        assert_eq!(
            ws_origin("https://chapaev.example"),
            "wss://chapaev.example"
        );
    }
}
