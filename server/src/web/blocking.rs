//! Running the store's (blocking) work off the async threads, and sorting
//! its errors into the client's (answered as they are) and the server's
//! (logged, answered `internal`).

use crate::accounts::AccountError;
use crate::refusal::Refusal;
use actix_web::web;
use tracing::error;

/// Runs `f` on a blocking thread; its error is the client's (`Ok` of a
/// refusal, sent as it is) or the server's (`Err`, logged, answered
/// `internal`), as `classify` says.
pub(crate) async fn blocking_with<T: Send + 'static, E: Send + 'static>(
    f: impl FnOnce() -> Result<T, E> + Send + 'static,
    classify: impl FnOnce(E) -> Result<Refusal, String>,
) -> Result<T, Refusal> {
    match web::block(f).await {
        Ok(Ok(t)) => Ok(t),
        Ok(Err(e)) => match classify(e) {
            Ok(refusal) => Err(refusal),
            Err(e) => {
                error!(error = %e, "store failure");
                Err(Refusal::internal())
            }
        },
        Err(e) => {
            error!(error = %e, "blocking task failed");
            Err(Refusal::internal())
        }
    }
}

/// Runs an account operation on a blocking thread: a refusal is the
/// client's, a store or randomness failure the server's.
pub(crate) async fn run_account<T: Send + 'static>(
    f: impl FnOnce() -> Result<T, AccountError> + Send + 'static,
) -> Result<T, Refusal> {
    blocking_with(f, |e| match e {
        AccountError::Refused(r) => Ok(r),
        AccountError::Store(e) => Err(e.to_string()),
        AccountError::Random(e) => Err(e.to_string()),
    })
    .await
}
