//! Putting the server together: logging, the store, the game runtime (the
//! threads that run match rooms: physics, bots, store writes), resuming
//! every unfinished match, the HTTP server on its own workers, and a
//! graceful shutdown on SIGTERM or Ctrl-C — rooms finish the move in hand
//! (so every accepted move is stored), connections close, the write-ahead
//! log is checkpointed.

use crate::config::Config;
use crate::metrics::Metrics;
use crate::play::hub::Hub;
use crate::store::StoreError;
use actix_web::{web, App, HttpServer};
use std::sync::Arc;
use std::time::Duration;
use tracing::{error, info, warn};

/// The server could not start or stop cleanly.
#[derive(Debug, thiserror::Error)]
pub enum AppError {
    #[error("bad log filter {0:?}: {1}")]
    Log(String, String),
    #[error(transparent)]
    Store(#[from] StoreError),
    #[error("cannot join the cluster: {0}")]
    Cluster(#[from] crate::play::cluster::ClusterError),
    #[error("cannot listen on {addr}: {source}")]
    Bind {
        addr: String,
        source: std::io::Error,
    },
    #[error("I/O: {0}")]
    Io(#[from] std::io::Error),
    #[error(transparent)]
    Backup(#[from] crate::backup::BackupError),
    #[error("--sdk-dir: {0}")]
    Sdk(#[from] crate::web::sdk::SdkError),
}

/// Installs the tracing subscriber (logs go to standard error).
pub fn init_logging(config: &Config) -> Result<(), AppError> {
    let filter = tracing_subscriber::EnvFilter::try_new(&config.log)
        .map_err(|e| AppError::Log(config.log.clone(), e.to_string()))?;
    // Already installed (tests): keep the first.
    let _ = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .try_init();
    Ok(())
}

/// A binary's whole `main`: flags from the command line and environment,
/// then [`run`] (or the command they name: `backup`, `restore`, whose
/// one-line report goes to standard output); an error is printed after
/// `program`'s name.
pub fn main(program: &str) -> std::process::ExitCode {
    use clap::Parser;
    let config = Config::parse();
    let done = match &config.command {
        Some(command) => init_logging(&config).and_then(|()| {
            println!("{}", crate::backup::run(command, &config)?);
            Ok(())
        }),
        None => run(config),
    };
    match done {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{program}: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

/// Runs the server until SIGTERM or Ctrl-C.
pub fn run(config: Config) -> Result<(), AppError> {
    init_logging(&config)?;
    let store = crate::store::open(&config)?;
    let metrics = Arc::new(Metrics::default());
    let game_rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(config.game_threads as usize)
        .thread_name("game")
        .enable_all()
        .build()?;
    let hub = Hub::new(
        store.clone(),
        metrics,
        config.limits(),
        game_rt.handle().clone(),
    );
    if let (Some(node), Some(db), Some(redis)) = (
        config.cluster_node(),
        &config.database_url,
        &config.redis_url,
    ) {
        let lease = Duration::from_secs(config.lease_seconds);
        let cluster = crate::play::cluster::Cluster::connect(
            node,
            config.public_url.clone(),
            db,
            redis,
            lease,
            game_rt.handle(),
        )?;
        hub.set_cluster(cluster.clone());
        cluster.start(&hub, game_rt.handle());
        info!(
            node = cluster.node(),
            lease_seconds = config.lease_seconds,
            "joined the cluster"
        );
    }
    // Live matches first and all of them (on a node of a cluster, those
    // no other node plays); open ones wait in the store.
    let resumed = game_rt.block_on(hub.resume_all())?;
    info!(
        resumed,
        store = store.backend(),
        "store opened; live matches resumed"
    );
    info!(
        workers = hub.hosted().workers(),
        hosted_seats = config.hosted_matches,
        "hosted bots' budget"
    );
    game_rt.spawn(expire_open_matches(
        hub.clone(),
        Duration::from_secs(config.open_match_expiry_seconds),
    ));

    let streams = {
        let _in_game_rt = game_rt.enter();
        crate::web::stream::Streams::start(hub.clone(), config.lobby_limits())
    };
    let served =
        actix_web::rt::System::new().block_on(serve(&config, hub.clone(), streams, &game_rt));
    // Rooms were stopped by the signal handler; make sure of it.
    game_rt.block_on(hub.shutdown(Duration::from_secs(config.shutdown_seconds)));
    game_rt.shutdown_timeout(Duration::from_secs(config.shutdown_seconds));
    if let Err(e) = store.checkpoint() {
        error!(error = %e, "final checkpoint failed");
    }
    info!("stopped");
    served
}

async fn serve(
    config: &Config,
    hub: Hub,
    streams: crate::web::stream::Streams,
    game_rt: &tokio::runtime::Runtime,
) -> Result<(), AppError> {
    let limit = config.max_message_bytes;
    let data = web::Data::new(hub.clone());
    let streams = web::Data::new(streams);
    let simulations = web::Data::new(crate::web::ratelimit::AddressLimiter::new(
        config.simulate_per_sec,
        config.simulate_burst,
    ));
    let creations = web::Data::new(crate::web::reply::Creations(
        crate::web::ratelimit::AddressLimiter::new(config.create_per_sec, config.create_burst),
    ));
    let origins = web::Data::new(crate::web::origin::Origins::new(&config.allowed_origins));
    let sdk = web::Data::new(crate::web::sdk::Served(match &config.sdk_dir {
        Some(dir) => {
            let sdk = crate::web::sdk::Sdk::load(dir)?;
            info!(dir = %dir.display(), files = ?sdk.names().collect::<Vec<_>>(), "serving the SDK at /sdk/");
            Some(Arc::new(sdk))
        }
        None => None,
    }));
    let proxies = web::Data::new(crate::web::client_addr::TrustedProxies::new(
        config.trusted_proxy.clone(),
    ));
    let server = HttpServer::new(move || {
        App::new()
            .app_data(data.clone())
            .app_data(streams.clone())
            .app_data(origins.clone())
            .app_data(proxies.clone())
            .app_data(sdk.clone())
            .wrap(actix_web::middleware::from_fn(crate::web::origin::check))
            .app_data(simulations.clone())
            .app_data(creations.clone())
            .app_data(web::PayloadConfig::new(limit))
            .wrap(
                actix_web::middleware::ErrorHandlers::new()
                    .handler(actix_web::http::StatusCode::PAYLOAD_TOO_LARGE, move |res| {
                        crate::web::reply::too_large_as_json(res, limit)
                    }),
            )
            .configure(crate::web::routes)
    })
    .on_connect(crate::web::ws::on_connect)
    .workers(config.http_workers as usize)
    .disable_signals()
    .shutdown_timeout(config.shutdown_seconds)
    .bind(&config.addr)
    .map_err(|source| AppError::Bind {
        addr: config.addr.clone(),
        source,
    })?;
    for addr in server.addrs() {
        info!(%addr, "listening");
        if let Err(why) = crate::web::assets::web_client() {
            if why.skipped {
                info!(
                    reason = why.reason,
                    "no web client embedded (skipped on purpose)"
                );
            } else {
                warn!(
                    reason = why.reason,
                    "no web client embedded: `/` serves a page saying why"
                );
            }
        }
        // The one line on standard output: tools and tests read the address here.
        println!("listening on http://{addr}");
    }
    let server = server.run();
    let handle = server.handle();
    let within = Duration::from_secs(config.shutdown_seconds);
    game_rt.spawn(async move {
        wait_for_signal().await;
        info!("shutting down: finishing in-flight moves");
        hub.shutdown(within).await;
        handle.stop(true).await;
    });
    server.await?;
    Ok(())
}

/// Deletes stale open matches now and then every minute, for as long as
/// the server runs.
async fn expire_open_matches(hub: Hub, after: Duration) {
    let mut every = tokio::time::interval(Duration::from_secs(60));
    loop {
        every.tick().await;
        match hub.expire_open(after).await {
            Ok(0) => {}
            Ok(n) => info!(expired = n, "open matches nobody joined expired"),
            Err(e) => error!(error = %e, "expiring open matches failed"),
        }
    }
}

async fn wait_for_signal() {
    #[cfg(unix)]
    {
        use tokio::signal::unix::{signal, SignalKind};
        match signal(SignalKind::terminate()) {
            Ok(mut term) => {
                tokio::select! {
                    _ = term.recv() => {},
                    _ = tokio::signal::ctrl_c() => {},
                }
            }
            Err(e) => {
                error!(error = %e, "cannot watch SIGTERM; Ctrl-C only");
                let _ = tokio::signal::ctrl_c().await;
            }
        }
    }
    #[cfg(not(unix))]
    {
        let _ = tokio::signal::ctrl_c().await;
    }
}
