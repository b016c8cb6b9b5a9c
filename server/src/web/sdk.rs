//! The bot-author packages this server hands out at `/sdk/`: the Python
//! wheel and the npm tarball of the `chapaev` simulator, built from the
//! same source as the server, so a bot simulates with exactly its physics
//! and no author needs a Rust toolchain.
//!
//! `scripts/build-sdk` builds them into a folder with a manifest,
//! `sdk.json`: the physics and protocol versions they were built under and
//! each file's name, kind and SHA-256. `--sdk-dir DIR` loads that folder
//! at startup ([`Sdk::load`]): a manifest of another physics version, a
//! file whose hash does not match, or a name that is not a plain file name
//! stops the server with a clear error, so it never hands out a simulator
//! that disagrees with it. The files are then served from memory:
//!
//! - `GET /sdk/` — the manifest as JSON, each file with its address and the
//!   command that installs it from this server;
//! - `GET /sdk/NAME` — the file, with its SHA-256 as the ETag.
//!
//! Without `--sdk-dir` (or for a name not in the manifest) the answer is
//! `404 no-such-file`, saying what the operator can do.

use crate::refusal::Refusal;
use crate::web::reply::refused;
use actix_web::http::header;
use actix_web::{web, HttpRequest, HttpResponse};
use game::protocol::ErrorCode;
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The manifest's file name inside the SDK folder.
pub const MANIFEST: &str = "sdk.json";

/// The largest package file loaded (a wheel or tarball is a few MB).
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// What kind of package a file is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Kind {
    /// A Python wheel: `pip install URL`.
    PythonWheel,
    /// An npm tarball: `npm install URL`.
    NpmTarball,
}

impl Kind {
    fn content_type(self) -> &'static str {
        match self {
            Kind::PythonWheel => "application/zip",
            Kind::NpmTarball => "application/gzip",
        }
    }

    fn installer(self) -> &'static str {
        match self {
            Kind::PythonWheel => "pip install",
            Kind::NpmTarball => "npm install",
        }
    }
}

/// `sdk.json` as `scripts/build-sdk` writes it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    pub physics_version: u32,
    pub protocol_version: u32,
    pub files: Vec<ManifestFile>,
}

/// One package in the manifest.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManifestFile {
    pub name: String,
    pub kind: Kind,
    /// Lower-case hex.
    pub sha256: String,
}

/// Why an SDK folder was not loaded.
#[derive(Debug, thiserror::Error)]
pub enum SdkError {
    #[error("cannot read {path}: {source}")]
    Read {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{path} is not an SDK manifest: {source}")]
    Manifest {
        path: PathBuf,
        #[source]
        source: serde_json::Error,
    },
    #[error("the SDK in {dir} was built for physics version {built}, but this server plays version {ours}: rebuild it with scripts/build-sdk")]
    Physics { dir: PathBuf, built: u32, ours: u32 },
    #[error("the SDK in {dir} was built for protocol version {built}, but this server speaks version {ours}: rebuild it with scripts/build-sdk")]
    Protocol { dir: PathBuf, built: u32, ours: u32 },
    #[error("the SDK manifest names {name:?}, which is not a plain file name")]
    BadName { name: String },
    #[error("the SDK manifest names {name:?} twice")]
    Duplicate { name: String },
    #[error("{path} is {bytes} bytes, above the limit of {MAX_FILE_BYTES}")]
    TooLarge { path: PathBuf, bytes: u64 },
    #[error("{path} does not match its SHA-256 in the manifest (it has {actual})")]
    Hash { path: PathBuf, actual: String },
}

/// One package, loaded.
#[derive(Debug)]
struct Package {
    name: String,
    kind: Kind,
    sha256: String,
    bytes: web::Bytes,
}

/// The packages a server hands out, checked and in memory.
#[derive(Debug)]
pub struct Sdk {
    physics_version: u32,
    protocol_version: u32,
    packages: Vec<Package>,
}

/// What `/sdk/` serves: an SDK, or none (no `--sdk-dir`).
#[derive(Clone, Debug, Default)]
pub struct Served(pub Option<Arc<Sdk>>);

/// A file name that is safe in a URL path segment and on disk: letters,
/// digits, `.`, `_`, `-` and `+`, not starting with a dot.
fn plain_name(name: &str) -> bool {
    !name.is_empty()
        && name.len() <= 200
        && !name.starts_with('.')
        && name
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || matches!(b, b'.' | b'_' | b'-' | b'+'))
}

fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

impl Sdk {
    /// Loads and checks the SDK folder `dir` (see the module's doc).
    pub fn load(dir: &Path) -> Result<Sdk, SdkError> {
        let path = dir.join(MANIFEST);
        let text = std::fs::read(&path).map_err(|source| SdkError::Read {
            path: path.clone(),
            source,
        })?;
        let manifest: Manifest =
            serde_json::from_slice(&text).map_err(|source| SdkError::Manifest {
                path: path.clone(),
                source,
            })?;
        if manifest.physics_version != game::PHYSICS_VERSION {
            return Err(SdkError::Physics {
                dir: dir.to_path_buf(),
                built: manifest.physics_version,
                ours: game::PHYSICS_VERSION,
            });
        }
        if manifest.protocol_version != game::protocol::PROTOCOL_VERSION {
            return Err(SdkError::Protocol {
                dir: dir.to_path_buf(),
                built: manifest.protocol_version,
                ours: game::protocol::PROTOCOL_VERSION,
            });
        }
        let mut packages: Vec<Package> = Vec::with_capacity(manifest.files.len());
        for file in manifest.files {
            if !plain_name(&file.name) {
                return Err(SdkError::BadName { name: file.name });
            }
            if packages.iter().any(|p| p.name == file.name) {
                return Err(SdkError::Duplicate { name: file.name });
            }
            let path = dir.join(&file.name);
            let read = |source| SdkError::Read {
                path: path.clone(),
                source,
            };
            let bytes = std::fs::metadata(&path).map_err(read)?.len();
            if bytes > MAX_FILE_BYTES {
                return Err(SdkError::TooLarge { path, bytes });
            }
            let data = std::fs::read(&path).map_err(read)?;
            let actual = sha256_hex(&data);
            if !actual.eq_ignore_ascii_case(&file.sha256) {
                return Err(SdkError::Hash { path, actual });
            }
            packages.push(Package {
                name: file.name,
                kind: file.kind,
                sha256: actual,
                bytes: web::Bytes::from(data),
            });
        }
        Ok(Sdk {
            physics_version: manifest.physics_version,
            protocol_version: manifest.protocol_version,
            packages,
        })
    }

    /// The names of the packages, in the manifest's order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.packages.iter().map(|p| p.name.as_str())
    }
}

/// Registers `/sdk/` and its files.
pub fn routes(cfg: &mut web::ServiceConfig) {
    cfg.route("/sdk", web::get().to(index))
        .route("/sdk/", web::get().to(index))
        .route("/sdk/{name}", web::get().to(file));
}

fn no_sdk() -> HttpResponse {
    refused(&Refusal::new(
        ErrorCode::NoSuchFile,
        "this server hands out no SDK: its operator can build one with scripts/build-sdk and start the server with --sdk-dir",
    ))
}

/// One package in the index.
#[derive(Serialize)]
struct IndexFile<'a> {
    name: &'a str,
    kind: Kind,
    bytes: usize,
    sha256: &'a str,
    url: String,
    install: String,
}

/// `GET /sdk/`: the manifest, with addresses on this server.
async fn index(req: HttpRequest, served: web::Data<Served>) -> HttpResponse {
    let Some(sdk) = &served.0 else {
        return no_sdk();
    };
    let info = req.connection_info();
    let base = format!("{}://{}/sdk/", info.scheme(), info.host());
    let files: Vec<IndexFile> = sdk
        .packages
        .iter()
        .map(|p| {
            let url = format!("{base}{}", p.name);
            IndexFile {
                name: &p.name,
                kind: p.kind,
                bytes: p.bytes.len(),
                sha256: &p.sha256,
                install: format!("{} {url}", p.kind.installer()),
                url,
            }
        })
        .collect();
    HttpResponse::Ok().json(serde_json::json!({
        "physics_version": sdk.physics_version,
        "protocol_version": sdk.protocol_version,
        "files": files,
    }))
}

/// `GET /sdk/NAME`: one package.
async fn file(
    req: HttpRequest,
    name: web::Path<String>,
    served: web::Data<Served>,
) -> HttpResponse {
    let Some(sdk) = &served.0 else {
        return no_sdk();
    };
    let Some(p) = sdk.packages.iter().find(|p| p.name == *name) else {
        return refused(&Refusal::new(
            ErrorCode::NoSuchFile,
            "no such package: GET /sdk/ lists them",
        ));
    };
    let etag = format!("\"{}\"", p.sha256);
    let fresh = req
        .headers()
        .get(header::IF_NONE_MATCH)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|v| v.split(',').any(|t| t.trim() == etag));
    if fresh {
        return HttpResponse::NotModified()
            .insert_header((header::ETAG, etag))
            .finish();
    }
    HttpResponse::Ok()
        .content_type(p.kind.content_type())
        .insert_header((header::ETAG, etag))
        .insert_header((header::CACHE_CONTROL, "no-cache"))
        .insert_header((
            header::CONTENT_DISPOSITION,
            format!("attachment; filename=\"{}\"", p.name),
        ))
        .body(p.bytes.clone())
}

#[cfg(test)]
mod tests {
    use super::*;
    use actix_web::{test as web_test, App};

    /// A folder holding `files` and a manifest of them under `physics`.
    fn folder(files: &[(&str, Kind, &[u8])], physics: u32) -> tempfile::TempDir {
        let dir = tempfile::tempdir().unwrap();
        let manifest = Manifest {
            physics_version: physics,
            protocol_version: game::protocol::PROTOCOL_VERSION,
            files: files
                .iter()
                .map(|(name, kind, bytes)| {
                    std::fs::write(dir.path().join(name), bytes).unwrap();
                    ManifestFile {
                        name: name.to_string(),
                        kind: *kind,
                        sha256: sha256_hex(bytes),
                    }
                })
                .collect(),
        };
        std::fs::write(
            dir.path().join(MANIFEST),
            serde_json::to_vec(&manifest).unwrap(),
        )
        .unwrap();
        dir
    }

    const WHEEL: &str = "chapaev_py-0.1.0-cp39-abi3-manylinux_2_34_x86_64.whl";

    #[test]
    fn an_sdk_of_another_physics_version_is_refused_at_load() {
        let dir = folder(
            &[(WHEEL, Kind::PythonWheel, b"wheel")],
            game::PHYSICS_VERSION + 1,
        );
        let err = Sdk::load(dir.path()).unwrap_err();
        assert!(matches!(err, SdkError::Physics { .. }), "{err}");
        assert!(err.to_string().contains("scripts/build-sdk"), "{err}");
    }

    #[test]
    fn a_package_changed_after_the_manifest_is_refused_at_load() {
        let dir = folder(
            &[("chapaev-0.1.0.tgz", Kind::NpmTarball, b"tarball")],
            game::PHYSICS_VERSION,
        );
        std::fs::write(dir.path().join("chapaev-0.1.0.tgz"), b"tampered").unwrap();
        let err = Sdk::load(dir.path()).unwrap_err();
        assert!(matches!(err, SdkError::Hash { .. }), "{err}");
    }

    #[test]
    fn a_manifest_naming_a_path_outside_the_folder_is_refused_at_load() {
        for name in ["../etc/passwd", "/etc/passwd", "a/b.whl", ".hidden", ""] {
            let dir = folder(&[], game::PHYSICS_VERSION);
            let manifest = serde_json::json!({
                "physics_version": game::PHYSICS_VERSION,
                "protocol_version": game::protocol::PROTOCOL_VERSION,
                "files": [{"name": name, "kind": "npm-tarball", "sha256": "00"}],
            });
            std::fs::write(dir.path().join(MANIFEST), manifest.to_string()).unwrap();
            let err = Sdk::load(dir.path()).unwrap_err();
            assert!(matches!(err, SdkError::BadName { .. }), "{name:?}: {err}");
        }
    }

    #[test]
    fn a_missing_or_malformed_manifest_is_a_clear_error() {
        let dir = tempfile::tempdir().unwrap();
        assert!(matches!(
            Sdk::load(dir.path()).unwrap_err(),
            SdkError::Read { .. }
        ));
        std::fs::write(dir.path().join(MANIFEST), b"{\"physics_version\": NaN}").unwrap();
        assert!(matches!(
            Sdk::load(dir.path()).unwrap_err(),
            SdkError::Manifest { .. }
        ));
    }

    #[actix_web::test]
    async fn the_index_lists_each_package_with_its_install_command_and_the_file_is_served_by_hash()
    {
        let dir = folder(
            &[
                (WHEEL, Kind::PythonWheel, b"wheel bytes"),
                ("chapaev-0.1.0.tgz", Kind::NpmTarball, b"tarball bytes"),
            ],
            game::PHYSICS_VERSION,
        );
        let sdk = Sdk::load(dir.path()).unwrap();
        let app = web_test::init_service(
            App::new()
                .app_data(web::Data::new(Served(Some(Arc::new(sdk)))))
                .configure(routes),
        )
        .await;
        let req = web_test::TestRequest::get()
            .uri("/sdk/")
            .insert_header((header::HOST, "chapaev.example:8080"))
            .to_request();
        let index: serde_json::Value = web_test::call_and_read_body_json(&app, req).await;
        assert_eq!(index["physics_version"], game::PHYSICS_VERSION);
        assert_eq!(
            index["files"][0]["install"],
            format!("pip install http://chapaev.example:8080/sdk/{WHEEL}")
        );
        assert_eq!(index["files"][1]["kind"], "npm-tarball");

        let req = web_test::TestRequest::get()
            .uri("/sdk/chapaev-0.1.0.tgz")
            .to_request();
        let res = web_test::call_service(&app, req).await;
        assert_eq!(res.status(), 200);
        let etag = res.headers().get(header::ETAG).unwrap().clone();
        assert_eq!(
            etag.to_str().unwrap(),
            format!("\"{}\"", sha256_hex(b"tarball bytes"))
        );
        assert_eq!(web_test::read_body(res).await, &b"tarball bytes"[..]);

        let req = web_test::TestRequest::get()
            .uri("/sdk/chapaev-0.1.0.tgz")
            .insert_header((header::IF_NONE_MATCH, etag))
            .to_request();
        assert_eq!(web_test::call_service(&app, req).await.status(), 304);

        for missing in ["/sdk/nothing.whl", "/sdk/..%2Fsdk.json", "/sdk/sdk.json"] {
            let req = web_test::TestRequest::get().uri(missing).to_request();
            let res = web_test::call_service(&app, req).await;
            assert_eq!(res.status(), 404, "{missing}");
        }
    }

    #[actix_web::test]
    async fn a_server_without_an_sdk_says_how_to_get_one() {
        let app = web_test::init_service(
            App::new()
                .app_data(web::Data::new(Served(None)))
                .configure(routes),
        )
        .await;
        let req = web_test::TestRequest::get().uri("/sdk/").to_request();
        let res = web_test::call_service(&app, req).await;
        assert_eq!(res.status(), 404);
        let body: serde_json::Value = web_test::read_body_json(res).await;
        assert_eq!(body["code"], "no-such-file");
        assert!(
            body["message"].as_str().unwrap().contains("--sdk-dir"),
            "{body}"
        );
    }
}
