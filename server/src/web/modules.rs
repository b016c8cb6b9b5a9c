//! The HTTP API of [`crate::accounts::modules`]: a bot account, proved by
//! its key, uploads its hosted module (`PUT /api/accounts/me/module`, the
//! WebAssembly bytes as the body, at most
//! [`MAX_MODULE_BYTES`](crate::accounts::modules::MAX_MODULE_BYTES)), lists
//! its versions (`GET /api/accounts/me/modules`) and makes one active
//! (`PUT /api/accounts/me/modules/active`, `{"hash": "…"}`) or deletes
//! one that is not active (`DELETE /api/accounts/me/modules/{hash}`). The
//! body of an upload is read here with its own limit, above the JSON
//! bodies' one, and refused as soon as it passes it.

use crate::accounts::modules::MAX_MODULE_BYTES;
use crate::play::hub::Hub;
use crate::web::auth::proven;
use crate::web::blocking::run_account;
use crate::web::reply::{json, read_body, refused};
use actix_web::http::StatusCode;
use actix_web::{web, HttpRequest, HttpResponse};
use futures_util::StreamExt;
use game::protocol::{ErrorCode, Refusal};
use serde::Deserialize;

/// Registers the module routes.
pub fn routes(cfg: &mut web::ServiceConfig) {
    cfg.route("/api/accounts/me/module", web::put().to(upload))
        .route("/api/accounts/me/modules", web::get().to(list))
        .route("/api/accounts/me/modules/active", web::put().to(activate))
        .route("/api/accounts/me/modules/{hash}", web::delete().to(delete));
}

fn too_large() -> Refusal {
    Refusal::new(
        ErrorCode::MessageTooLarge,
        format!("a module is at most {MAX_MODULE_BYTES} bytes"),
    )
}

/// The upload's body, refused (without reading on) once it is known to
/// pass the limit: from its `Content-Length`, or as it arrives.
async fn read_module(req: &HttpRequest, mut payload: web::Payload) -> Result<Vec<u8>, Refusal> {
    let declared = req
        .headers()
        .get(actix_web::http::header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.trim().parse::<u64>().ok());
    if declared.is_some_and(|n| n > MAX_MODULE_BYTES as u64) {
        return Err(too_large());
    }
    let mut bytes = Vec::new();
    while let Some(chunk) = payload.next().await {
        let chunk = chunk.map_err(|e| {
            Refusal::new(
                ErrorCode::BadMessage,
                format!("the body could not be read: {e}"),
            )
        })?;
        if bytes.len() + chunk.len() > MAX_MODULE_BYTES {
            return Err(too_large());
        }
        bytes.extend_from_slice(&chunk);
    }
    Ok(bytes)
}

/// `PUT /api/accounts/me/module`: `201` and the version for a new module,
/// `200` for one the account had (made active again).
async fn upload(req: HttpRequest, hub: web::Data<Hub>, payload: web::Payload) -> HttpResponse {
    let stored = async {
        let (_, account) = proven(&req, &hub).await?;
        let bytes = read_module(&req, payload).await?;
        let store = hub.store().clone();
        let name = account.name.clone();
        let (new, version) = run_account(move || store.upload_module(&account, &bytes)).await?;
        tracing::info!(account = %name, hash = %version.hash, size = version.size, new, "bot module uploaded");
        Ok((new, version))
    };
    match stored.await {
        Ok((true, v)) => json(StatusCode::CREATED, &v),
        Ok((false, v)) => json(StatusCode::OK, &v),
        Err(r) => refused(&r),
    }
}

async fn list(req: HttpRequest, hub: web::Data<Hub>) -> HttpResponse {
    let listed = async {
        let (_, account) = proven(&req, &hub).await?;
        let store = hub.store().clone();
        run_account(move || store.module_versions(&account)).await
    };
    match listed.await {
        Ok(versions) => json(StatusCode::OK, &versions),
        Err(r) => refused(&r),
    }
}

/// `PUT /api/accounts/me/modules/active`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ActivateBody {
    hash: String,
}

async fn activate(req: HttpRequest, hub: web::Data<Hub>, bytes: web::Bytes) -> HttpResponse {
    let made = async {
        let body: ActivateBody = read_body(&bytes)?;
        let (_, account) = proven(&req, &hub).await?;
        let store = hub.store().clone();
        let name = account.name.clone();
        let version = run_account(move || store.activate_version(&account, &body.hash)).await?;
        tracing::info!(account = %name, hash = %version.hash, "bot module version made active");
        Ok(version)
    };
    match made.await {
        Ok(v) => json(StatusCode::OK, &v),
        Err(r) => refused(&r),
    }
}

async fn delete(req: HttpRequest, hub: web::Data<Hub>, hash: web::Path<String>) -> HttpResponse {
    let done = async {
        let (_, account) = proven(&req, &hub).await?;
        let store = hub.store().clone();
        let name = account.name.clone();
        let hash = hash.into_inner();
        let gone = hash.clone();
        run_account(move || store.delete_version(&account, &hash)).await?;
        tracing::info!(account = %name, hash = %gone, "bot module version deleted");
        Ok(())
    };
    match done.await {
        Ok(()) => HttpResponse::NoContent().finish(),
        Err(r) => refused(&r),
    }
}
