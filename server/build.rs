//! Builds the web client and embeds it in the server.
//!
//! A nested `cargo build -p web-client --target wasm32-unknown-unknown
//! --profile wasm-release` runs in a target folder of its own
//! (`<target>/web-client`, so it never waits on the lock the outer build
//! holds), with the outer build's variables that would steer it wrongly
//! removed. The page (`web-client/index.html`), our miniquad plugin
//! (`web-client/js/chapaev.js`), macroquad's loader (`js/mq_js_bundle.js`
//! from the very macroquad crate the client uses, found with `cargo
//! metadata`) and the wasm (as `chapaev.wasm`) are copied into `OUT_DIR`,
//! and `OUT_DIR/web_client.rs` names them with `include_bytes!` for
//! `src/assets.rs`. Each file is also compressed here, once, with brotli
//! (the `brotli` crate, quality 11) and with gzip (flate2, best
//! compression), so the server sends the copy a request accepts with its
//! `Content-Encoding` without compressing anything per request, and
//! the page asks for its scripts and wasm under `?v=<hash>` addresses that
//! change with every build (so they can be cached for good).
//!
//! The home-screen files are made here too: the icons (`build/icon.rs`,
//! 192 and 512 pixels), and the service worker (`web-client/js/sw.js`)
//! with this build's cache name and file addresses filled in.
//!
//! The server always builds: without the wasm target, or when the client
//! does not compile, a `cargo:warning` says what happened and what to run,
//! and the generated file holds the reason instead, so `/` serves the API
//! page with a note. `CHAPAEV_SKIP_WEB_CLIENT=1` skips the nested build on
//! purpose (fast iteration on the server alone).

use std::collections::HashMap;
use std::ffi::OsString;
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

#[path = "build/icon.rs"]
mod icon;

const WASM_TARGET: &str = "wasm32-unknown-unknown";
const PROFILE: &str = "wasm-release";
const SKIP_VAR: &str = "CHAPAEV_SKIP_WEB_CLIENT";

/// Why the client is not embedded.
#[derive(Debug, thiserror::Error)]
enum NotBuilt {
    #[error("{SKIP_VAR} is set: the nested web client build was skipped")]
    Skipped,
    #[error("the {WASM_TARGET} target is not installed; run `rustup target add {WASM_TARGET}` and build again")]
    NoTarget,
    #[error("`{command}` failed ({status}):\n{tail}")]
    BuildFailed {
        command: String,
        status: String,
        tail: String,
    },
    #[error("cannot run `{command}`: {source}")]
    Spawn {
        command: String,
        source: std::io::Error,
    },
    #[error("{0}")]
    Missing(String),
    #[error("drawing the {size} px icon: {source}")]
    Icon {
        size: u32,
        source: png::EncodingError,
    },
    #[error("{what}: {source}")]
    Io {
        what: String,
        source: std::io::Error,
    },
}

/// One embedded file: where it and its compressed copies lie in
/// `OUT_DIR`, its content hash and its ETag.
struct Copied {
    path: PathBuf,
    gzip: PathBuf,
    brotli: PathBuf,
    hash: String,
    etag: String,
}

fn main() {
    let manifest_dir = PathBuf::from(env_or_panic("CARGO_MANIFEST_DIR"));
    let workspace = manifest_dir
        .parent()
        .expect("server/ sits in the workspace")
        .to_path_buf();
    let out_dir = PathBuf::from(env_or_panic("OUT_DIR"));

    println!("cargo:rerun-if-env-changed={SKIP_VAR}");
    for watched in [
        "web-client/src",
        "web-client/js",
        "web-client/index.html",
        "web-client/assets",
        "web-client/locales",
        "web-client/manifest.webmanifest",
        "server/build",
        "web-client/Cargo.toml",
        "engine/src",
        "engine/Cargo.toml",
        "game/src",
        "game/Cargo.toml",
        "Cargo.toml",
        "Cargo.lock",
    ] {
        println!(
            "cargo:rerun-if-changed={}",
            workspace.join(watched).display()
        );
    }

    let generated = match build(&workspace, &out_dir) {
        Ok(files) => embedded(&files),
        Err(why) => {
            if !matches!(why, NotBuilt::Skipped) {
                for line in why.to_string().lines() {
                    println!("cargo:warning=web client not embedded: {line}");
                }
                println!(
                    "cargo:warning=the server will serve the API page at / instead of the game"
                );
            }
            fallback(&why)
        }
    };
    let path = out_dir.join("web_client.rs");
    if let Err(e) = std::fs::write(&path, generated) {
        panic!("cannot write {}: {e}", path.display());
    }
}

fn env_or_panic(name: &str) -> OsString {
    std::env::var_os(name).unwrap_or_else(|| panic!("cargo sets {name} for build scripts"))
}

/// Builds the client and copies its five files (and their gzipped copies)
/// into `OUT_DIR/web`.
fn build(workspace: &Path, out_dir: &Path) -> Result<HashMap<&'static str, Copied>, NotBuilt> {
    if std::env::var_os(SKIP_VAR).is_some_and(|v| !v.is_empty() && v != "0") {
        return Err(NotBuilt::Skipped);
    }
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let rustc = std::env::var_os("RUSTC").unwrap_or_else(|| "rustc".into());
    if let Some(target_libs) = wasm_target_libs(&rustc) {
        // Missing now: cargo reruns this script on every build until it
        // exists, so `rustup target add` is picked up without touching a file.
        println!("cargo:rerun-if-changed={}", target_libs.display());
        if !target_libs.is_dir() {
            return Err(NotBuilt::NoTarget);
        }
    }

    let target_dir = client_target_dir(workspace);
    let started = Instant::now();
    let wasm = cargo_build(&cargo, workspace, &target_dir)?;
    println!(
        "web client built in {:.1} s: {}",
        started.elapsed().as_secs_f64(),
        wasm.display()
    );
    let bundle = mq_js_bundle(&cargo, workspace)?;

    let web = out_dir.join("web");
    std::fs::create_dir_all(&web).map_err(|source| NotBuilt::Io {
        what: format!("creating {}", web.display()),
        source,
    })?;
    let mut files = HashMap::new();
    for (key, from, name) in [
        (
            "chapaev_js",
            workspace.join("web-client/js/chapaev.js"),
            "chapaev.js",
        ),
        ("mq_js_bundle", bundle, "mq_js_bundle.js"),
        ("wasm", wasm, "chapaev.wasm"),
        (
            "favicon",
            workspace.join("web-client/assets/favicon.svg"),
            "favicon.svg",
        ),
        (
            "manifest",
            workspace.join("web-client/manifest.webmanifest"),
            "manifest.webmanifest",
        ),
    ] {
        let bytes = read(&from)?;
        files.insert(key, store(bytes, &web.join(name))?);
    }
    for (key, size) in [("icon_192", 192), ("icon_512", 512)] {
        let png = icon::png(size).map_err(|source| NotBuilt::Icon { size, source })?;
        files.insert(key, store(png, &web.join(format!("icon-{size}.png")))?);
    }
    // The page names each file with its hash, so a new build is a new address.
    let mut page =
        String::from_utf8_lossy(&read(&workspace.join("web-client/index.html"))?).into_owned();
    for (key, name) in [
        ("chapaev_js", "chapaev.js"),
        ("mq_js_bundle", "mq_js_bundle.js"),
        ("wasm", "chapaev.wasm"),
        ("favicon", "favicon.svg"),
        ("manifest", "manifest.webmanifest"),
    ] {
        let versioned = format!("{name}?v={}", files[key].hash);
        page = page.replace(&format!("\"{name}\""), &format!("\"{versioned}\""));
    }
    let page = page.replace("__CHAPAEV_LOADING__", &loader_words(workspace)?);
    let page = store(page.into_bytes(), &web.join("index.html"))?;
    // The service worker caches this build's files under their addresses.
    let mut cached = vec!["/".to_string()];
    for (key, name) in [
        ("chapaev_js", "chapaev.js"),
        ("mq_js_bundle", "mq_js_bundle.js"),
        ("wasm", "chapaev.wasm"),
        ("favicon", "favicon.svg"),
        ("manifest", "manifest.webmanifest"),
    ] {
        cached.push(format!("/{name}?v={}", files[key].hash));
    }
    cached.extend(["/icon-192.png".to_string(), "/icon-512.png".to_string()]);
    let worker = String::from_utf8_lossy(&read(&workspace.join("web-client/js/sw.js"))?)
        .replace("__CHAPAEV_BUILD__", &page.hash)
        .replace(
            "__CHAPAEV_FILES__",
            &serde_json::Value::from(cached).to_string(),
        );
    files.insert("index_html", page);
    files.insert(
        "service_worker",
        store(worker.into_bytes(), &web.join("sw.js"))?,
    );
    Ok(files)
}

/// The page's loader's words in each of the client's languages, as a JSON
/// object (`{"en": "Loading Chapaev…", "ru": …}`): the message
/// `page-loading` of each Fluent file in `web-client/locales`, so the words
/// shown before the game has loaded are translated where all its others
/// are.
fn loader_words(workspace: &Path) -> Result<String, NotBuilt> {
    let mut words = serde_json::Map::new();
    for lang in ["en", "ru"] {
        let path = workspace.join(format!("web-client/locales/{lang}.ftl"));
        let ftl = String::from_utf8_lossy(&read(&path)?).into_owned();
        let Some(text) = ftl
            .lines()
            .find_map(|l| l.strip_prefix("page-loading ="))
            .map(str::trim)
        else {
            return Err(NotBuilt::Io {
                what: format!("reading the message page-loading from {}", path.display()),
                source: std::io::Error::new(std::io::ErrorKind::NotFound, "no such message"),
            });
        };
        words.insert(lang.to_string(), text.into());
    }
    Ok(serde_json::Value::Object(words).to_string())
}

/// `<sysroot>/lib/rustlib/wasm32-unknown-unknown`, where the target's
/// standard library lives once installed (`None`: rustc could not say).
fn wasm_target_libs(rustc: &OsString) -> Option<PathBuf> {
    let out = Command::new(rustc)
        .args(["--print", "sysroot"])
        .output()
        .ok()?;
    if !out.status.success() {
        return None;
    }
    let sysroot = String::from_utf8(out.stdout).ok()?;
    Some(
        Path::new(sysroot.trim())
            .join("lib/rustlib")
            .join(WASM_TARGET),
    )
}

/// The nested build's own target folder, beside the outer build's.
fn client_target_dir(workspace: &Path) -> PathBuf {
    let outer = match std::env::var_os("CARGO_TARGET_DIR") {
        Some(dir) if !dir.is_empty() => {
            let dir = PathBuf::from(dir);
            if dir.is_absolute() {
                dir
            } else {
                workspace.join(dir)
            }
        }
        _ => workspace.join("target"),
    };
    outer.join("web-client")
}

/// A cargo command for the nested build: run from the workspace, without
/// the variables the outer build set for this script (or inherited) that
/// would change what the nested one builds, for which target, where, or
/// under which wrapper (`cargo clippy` sets `RUSTC_WORKSPACE_WRAPPER` and
/// `CLIPPY_ARGS`; flags meant for the host must not reach the wasm).
fn nested(cargo: &OsString, workspace: &Path) -> Command {
    const EXACT: &[&str] = &[
        "CARGO_ENCODED_RUSTFLAGS",
        "CARGO_ENCODED_RUSTDOCFLAGS",
        "RUSTFLAGS",
        "RUSTDOCFLAGS",
        "CARGO_BUILD_RUSTFLAGS",
        "CARGO_BUILD_TARGET",
        "CARGO_TARGET_DIR",
        "CARGO_BUILD_TARGET_DIR",
        "CARGO_MAKEFLAGS",
        "MAKEFLAGS",
        "MFLAGS",
        "OUT_DIR",
        "TARGET",
        "HOST",
        "PROFILE",
        "OPT_LEVEL",
        "DEBUG",
        "NUM_JOBS",
        "RUSTC_LINKER",
        "RUSTC_WORKSPACE_WRAPPER",
        "CLIPPY_ARGS",
        "CARGO_PRIMARY_PACKAGE",
        "CARGO_CRATE_NAME",
        "CARGO_RUSTC_CURRENT_DIR",
    ];
    const PREFIXES: &[&str] = &[
        "CARGO_CFG_",
        "CARGO_FEATURE_",
        "CARGO_PKG_",
        "CARGO_MANIFEST_",
        "CARGO_BIN_",
        "DEP_",
        "__CARGO",
    ];
    let mut cmd = Command::new(cargo);
    cmd.current_dir(workspace);
    for (name, _) in std::env::vars_os() {
        let Some(name) = name.to_str() else { continue };
        if EXACT.contains(&name) || PREFIXES.iter().any(|p| name.starts_with(p)) {
            cmd.env_remove(name);
        }
    }
    cmd
}

/// Runs the nested build; returns the wasm it produced.
fn cargo_build(cargo: &OsString, workspace: &Path, target_dir: &Path) -> Result<PathBuf, NotBuilt> {
    let mut cmd = nested(cargo, workspace);
    cmd.args([
        "build",
        "-p",
        "web-client",
        "--bin",
        "web-client",
        "--target",
        WASM_TARGET,
        "--profile",
        PROFILE,
        "--message-format",
        "json-render-diagnostics",
        "--target-dir",
    ])
    .arg(target_dir);
    let command = format!(
        "cargo build -p web-client --target {WASM_TARGET} --profile {PROFILE} --target-dir {}",
        target_dir.display()
    );
    let out = cmd.output().map_err(|source| NotBuilt::Spawn {
        command: command.clone(),
        source,
    })?;
    if !out.status.success() {
        let stderr = String::from_utf8_lossy(&out.stderr);
        if stderr.contains("target may not be installed") {
            return Err(NotBuilt::NoTarget);
        }
        // From the first error on (warnings before it are noise here).
        let lines: Vec<&str> = stderr.lines().collect();
        let first_error = lines.iter().position(|l| l.starts_with("error"));
        let shown = match first_error {
            Some(i) => &lines[i..(i + 20).min(lines.len())],
            None => &lines[lines.len().saturating_sub(20)..],
        };
        let tail = shown.join("\n");
        return Err(NotBuilt::BuildFailed {
            command,
            status: out.status.to_string(),
            tail,
        });
    }
    // The artifact message names the wasm; else where cargo puts it.
    let stdout = String::from_utf8_lossy(&out.stdout);
    let from_messages = stdout.lines().rev().find_map(|line| {
        let v: serde_json::Value = serde_json::from_str(line).ok()?;
        (v["reason"] == "compiler-artifact" && v["target"]["name"] == "web-client")
            .then(|| v["executable"].as_str().map(PathBuf::from))
            .flatten()
    });
    let wasm = from_messages.unwrap_or_else(|| {
        target_dir
            .join(WASM_TARGET)
            .join(PROFILE)
            .join("web-client.wasm")
    });
    if wasm.is_file() {
        Ok(wasm)
    } else {
        Err(NotBuilt::Missing(format!(
            "the nested build succeeded but {} is missing",
            wasm.display()
        )))
    }
}

/// `js/mq_js_bundle.js` of the macroquad the web client depends on.
fn mq_js_bundle(cargo: &OsString, workspace: &Path) -> Result<PathBuf, NotBuilt> {
    let command = "cargo metadata --format-version 1".to_string();
    let out = nested(cargo, workspace)
        .args(["metadata", "--format-version", "1"])
        .output()
        .map_err(|source| NotBuilt::Spawn {
            command: command.clone(),
            source,
        })?;
    if !out.status.success() {
        return Err(NotBuilt::BuildFailed {
            command,
            status: out.status.to_string(),
            tail: String::from_utf8_lossy(&out.stderr).into_owned(),
        });
    }
    let missing = |what: &str| NotBuilt::Missing(format!("cargo metadata: {what}"));
    let meta: serde_json::Value =
        serde_json::from_slice(&out.stdout).map_err(|e| missing(&e.to_string()))?;
    let packages = meta["packages"]
        .as_array()
        .ok_or_else(|| missing("no packages"))?;
    let id_of = |name: &str| {
        packages
            .iter()
            .filter(|p| p["name"] == name)
            .filter_map(|p| p["id"].as_str())
            .collect::<Vec<_>>()
    };
    let client = id_of("web-client");
    let macroquads = id_of("macroquad");
    // The macroquad in web-client's resolved dependencies (there could be several).
    let chosen = meta["resolve"]["nodes"]
        .as_array()
        .into_iter()
        .flatten()
        .filter(|node| node["id"].as_str().is_some_and(|id| client.contains(&id)))
        .flat_map(|node| node["dependencies"].as_array().into_iter().flatten())
        .filter_map(|dep| dep.as_str())
        .find(|dep| macroquads.contains(dep))
        .ok_or_else(|| missing("web-client does not depend on macroquad"))?;
    let manifest = packages
        .iter()
        .find(|p| p["id"] == chosen)
        .and_then(|p| p["manifest_path"].as_str())
        .ok_or_else(|| missing("macroquad has no manifest_path"))?;
    let bundle = Path::new(manifest)
        .parent()
        .ok_or_else(|| missing("macroquad's manifest_path has no folder"))?
        .join("js/mq_js_bundle.js");
    if bundle.is_file() {
        Ok(bundle)
    } else {
        Err(missing(&format!("{} is missing", bundle.display())))
    }
}

fn read(from: &Path) -> Result<Vec<u8>, NotBuilt> {
    std::fs::read(from).map_err(|source| NotBuilt::Io {
        what: format!("reading {}", from.display()),
        source,
    })
}

/// Writes `bytes` to `to` and their compressed copies beside it (`.gz`
/// and `.br`).
fn store(bytes: Vec<u8>, to: &Path) -> Result<Copied, NotBuilt> {
    let io = |what: String| move |source| NotBuilt::Io { what, source };
    std::fs::write(to, &bytes).map_err(io(format!("writing {}", to.display())))?;
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    gz.write_all(&bytes)
        .map_err(io(format!("compressing {}", to.display())))?;
    let packed = gz
        .finish()
        .map_err(io(format!("compressing {}", to.display())))?;
    let beside = |suffix: &str| {
        to.with_extension(format!(
            "{}.{suffix}",
            to.extension().and_then(|e| e.to_str()).unwrap_or("")
        ))
    };
    let gzip = beside("gz");
    std::fs::write(&gzip, &packed).map_err(io(format!("writing {}", gzip.display())))?;
    // Brotli's best: quality 11, a 4 MiB window (the wasm is a few MiB).
    let mut packed = Vec::new();
    let params = brotli::enc::BrotliEncoderParams {
        quality: 11,
        lgwin: 22,
        ..Default::default()
    };
    brotli::BrotliCompress(&mut bytes.as_slice(), &mut packed, &params)
        .map_err(io(format!("compressing {} with brotli", to.display())))?;
    let brotli = beside("br");
    std::fs::write(&brotli, &packed).map_err(io(format!("writing {}", brotli.display())))?;
    let hash = format!("{:016x}", fnv1a(&bytes));
    Ok(Copied {
        path: to.to_path_buf(),
        gzip,
        brotli,
        etag: format!("\"{hash}-{:x}\"", bytes.len()),
        hash,
    })
}

/// 64-bit FNV-1a: enough to tell one build's file from another's.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}

const HEADER: &str =
    "// Generated by server/build.rs: the embedded web client (see src/assets.rs).\n";

fn embedded(files: &HashMap<&'static str, Copied>) -> String {
    let mut code = String::from(HEADER);
    code.push_str("pub(crate) const WEB_CLIENT: Result<Bundle, NotBuilt> = Ok(Bundle {\n");
    for (key, content_type) in [
        ("index_html", "text/html; charset=utf-8"),
        ("chapaev_js", "text/javascript; charset=utf-8"),
        ("mq_js_bundle", "text/javascript; charset=utf-8"),
        ("wasm", "application/wasm"),
        ("favicon", "image/svg+xml"),
        ("manifest", "application/manifest+json"),
        ("service_worker", "text/javascript; charset=utf-8"),
        ("icon_192", "image/png"),
        ("icon_512", "image/png"),
    ] {
        let file = &files[key];
        let _ = writeln!(
            code,
            "    {key}: Asset {{ bytes: include_bytes!({:?}), gzip: include_bytes!({:?}), \
             brotli: include_bytes!({:?}), hash: {:?}, etag: {:?}, \
             content_type: {content_type:?} }},",
            file.path.display().to_string(),
            file.gzip.display().to_string(),
            file.brotli.display().to_string(),
            file.hash,
            file.etag,
        );
    }
    code.push_str("});\n");
    code
}

fn fallback(why: &NotBuilt) -> String {
    format!(
        "{HEADER}pub(crate) const WEB_CLIENT: Result<Bundle, NotBuilt> = Err(NotBuilt {{ reason: {:?}, skipped: {} }});\n",
        why.to_string(),
        matches!(why, NotBuilt::Skipped),
    )
}
