//! Loading a hosted bot's module: the size checked before anything is
//! parsed, the module validated and compiled once, its imports checked
//! against the host's (nothing but `chapaev.simulate` and
//! `chapaev.random`: a WASI import is refused by name), its exports
//! against [`crate::abi`]. A module that loads is ready to decide.

use crate::abi;
use crate::host::HostState;
use crate::limits::Limits;
use sha2::{Digest, Sha256};
use wasmi::{CompilationMode, Engine, ExternType, Linker, Module, ValType};

/// Why a module is refused.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    #[error("the module is {size} bytes, above the limit of {limit}")]
    TooLarge { size: usize, limit: usize },
    #[error("not a valid WebAssembly module: {0}")]
    Invalid(#[source] wasmi::Error),
    #[error("the module imports {module}.{name}: a hosted bot may import only chapaev.simulate and chapaev.random (no WASI, no clock, no files)")]
    ForbiddenImport { module: String, name: String },
    #[error("the import chapaev.{name} has the wrong type: {expected}")]
    WrongImport {
        name: String,
        expected: &'static str,
    },
    #[error("the module does not export {0:?}")]
    MissingExport(&'static str),
    #[error("the export {name:?} has the wrong type: expected {expected}")]
    WrongExport {
        name: &'static str,
        expected: &'static str,
    },
    #[error("the module's memory starts at {bytes} bytes, above the limit of {limit}")]
    MemoryTooLarge { bytes: u64, limit: usize },
    #[error("the host functions could not be defined: {0}")]
    Host(#[source] wasmi::Error),
}

/// Bytes in a WebAssembly page.
const PAGE: u64 = 65536;

/// A checked, compiled hosted bot.
pub struct BotModule {
    pub(crate) engine: Engine,
    pub(crate) module: Module,
    pub(crate) linker: Linker<HostState>,
    pub(crate) limits: Limits,
    hash: [u8; 32],
    size: usize,
}

impl std::fmt::Debug for BotModule {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("BotModule")
            .field("hash", &self.hash_hex())
            .field("size", &self.size)
            .finish()
    }
}

fn is_func(ty: &ExternType, params: &[ValType], results: &[ValType]) -> bool {
    matches!(ty, ExternType::Func(f) if f.params() == params && f.results() == results)
}

impl BotModule {
    /// Checks and compiles `bytes` under `limits`.
    pub fn load(bytes: &[u8], limits: &Limits) -> Result<BotModule, LoadError> {
        if bytes.len() > limits.max_module_bytes {
            return Err(LoadError::TooLarge {
                size: bytes.len(),
                limit: limits.max_module_bytes,
            });
        }
        let mut config = wasmi::Config::default();
        config
            .consume_fuel(true)
            // Everything compiled now: a module that loads has no
            // translation left to fail or to charge fuel for later.
            .compilation_mode(CompilationMode::Eager);
        let engine = Engine::new(&config);
        let module = Module::new(&engine, bytes).map_err(LoadError::Invalid)?;
        use ValType::{I32, I64};
        for import in module.imports() {
            let (m, name) = (import.module(), import.name());
            let expected: (&[ValType], &[ValType], &'static str) = match (m, name) {
                (abi::IMPORT_MODULE, abi::SIMULATE) => {
                    (&[I32, I32, I32, I32], &[I32], "(i32, i32, i32, i32) -> i32")
                }
                (abi::IMPORT_MODULE, abi::RANDOM) => (&[], &[I64], "() -> i64"),
                _ => {
                    return Err(LoadError::ForbiddenImport {
                        module: m.to_string(),
                        name: name.to_string(),
                    })
                }
            };
            if !is_func(import.ty(), expected.0, expected.1) {
                return Err(LoadError::WrongImport {
                    name: name.to_string(),
                    expected: expected.2,
                });
            }
        }
        let export = |name: &'static str| {
            module
                .exports()
                .find(|e| e.name() == name)
                .map(|e| e.ty().clone())
                .ok_or(LoadError::MissingExport(name))
        };
        let ExternType::Memory(memory) = export(abi::MEMORY)? else {
            return Err(LoadError::WrongExport {
                name: abi::MEMORY,
                expected: "a memory",
            });
        };
        let least = memory.minimum().saturating_mul(PAGE);
        if least > limits.max_memory_bytes as u64 {
            return Err(LoadError::MemoryTooLarge {
                bytes: least,
                limit: limits.max_memory_bytes,
            });
        }
        if !is_func(&export(abi::ALLOC)?, &[I32], &[I32]) {
            return Err(LoadError::WrongExport {
                name: abi::ALLOC,
                expected: "(i32) -> i32",
            });
        }
        if !is_func(&export(abi::DECIDE)?, &[I32, I32], &[I64]) {
            return Err(LoadError::WrongExport {
                name: abi::DECIDE,
                expected: "(i32, i32) -> i64",
            });
        }
        let linker = crate::host::linker(&engine).map_err(LoadError::Host)?;
        Ok(BotModule {
            engine,
            module,
            linker,
            limits: limits.clone(),
            hash: Sha256::digest(bytes).into(),
            size: bytes.len(),
        })
    }

    /// The SHA-256 of the module's bytes (its version's name).
    pub fn hash(&self) -> [u8; 32] {
        self.hash
    }

    /// The hash as 64 lowercase hex digits.
    pub fn hash_hex(&self) -> String {
        self.hash.iter().map(|b| format!("{b:02x}")).collect()
    }

    /// The module's size in bytes.
    pub fn size(&self) -> usize {
        self.size
    }

    /// The limits it runs under.
    pub fn limits(&self) -> &Limits {
        &self.limits
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(wat: &str) -> Result<BotModule, LoadError> {
        BotModule::load(&wat::parse_str(wat).unwrap(), &Limits::default())
    }

    const EXPORTS: &str = r#"
        (memory (export "memory") 1)
        (func (export "chapaev_alloc") (param i32) (result i32) i32.const 1024)
        (func (export "chapaev_decide") (param i32 i32) (result i64) i64.const 0)"#;

    #[test]
    fn a_module_with_the_three_exports_and_the_hosts_imports_loads_and_is_named_by_its_hash() {
        let text = format!(
            r#"(module
                (import "chapaev" "simulate" (func (param i32 i32 i32 i32) (result i32)))
                (import "chapaev" "random" (func (result i64)))
                {EXPORTS})"#
        );
        let m = load(&text).unwrap();
        assert_eq!(m.hash_hex().len(), 64);
        assert_eq!(m.size(), wat::parse_str(&text).unwrap().len());
    }

    #[test]
    fn a_module_of_100_megabytes_is_refused_before_it_is_parsed() {
        let huge = vec![0u8; 100 << 20];
        let err = BotModule::load(&huge, &Limits::default()).unwrap_err();
        assert!(
            matches!(err, LoadError::TooLarge { size, .. } if size == 100 << 20),
            "{err}"
        );
    }

    #[test]
    fn bytes_that_are_not_webassembly_are_refused_as_invalid() {
        let err = BotModule::load(b"\0asm garbage", &Limits::default()).unwrap_err();
        assert!(matches!(err, LoadError::Invalid(_)), "{err}");
    }

    #[test]
    fn a_module_importing_wasi_is_refused_by_the_imports_name() {
        let text = format!(
            r#"(module
                (import "wasi_snapshot_preview1" "fd_write" (func (param i32 i32 i32 i32) (result i32)))
                {EXPORTS})"#
        );
        let err = load(&text).unwrap_err();
        match &err {
            LoadError::ForbiddenImport { module, name } => {
                assert_eq!(
                    (module.as_str(), name.as_str()),
                    ("wasi_snapshot_preview1", "fd_write")
                )
            }
            other => panic!("{other}"),
        }
        assert!(err.to_string().contains("no WASI"), "{err}");
    }

    #[test]
    fn a_module_whose_memory_starts_above_the_limit_is_refused() {
        let text = r#"(module
            (memory (export "memory") 16384)
            (func (export "chapaev_alloc") (param i32) (result i32) i32.const 0)
            (func (export "chapaev_decide") (param i32 i32) (result i64) i64.const 0))"#;
        let err = load(text).unwrap_err();
        assert!(
            matches!(err, LoadError::MemoryTooLarge { bytes, .. } if bytes == 1 << 30),
            "{err}"
        );
    }

    #[test]
    fn a_host_import_of_the_wrong_type_is_refused() {
        let text = format!(r#"(module (import "chapaev" "random" (func (result i32))) {EXPORTS})"#);
        assert!(matches!(
            load(&text).unwrap_err(),
            LoadError::WrongImport { .. }
        ));
    }

    #[test]
    fn a_module_with_wrong_or_missing_exports_is_refused_naming_the_export() {
        let missing = r#"(module
            (memory (export "memory") 1)
            (func (export "chapaev_alloc") (param i32) (result i32) i32.const 0))"#;
        assert!(matches!(
            load(missing).unwrap_err(),
            LoadError::MissingExport("chapaev_decide")
        ));
        let wrong = r#"(module
            (memory (export "memory") 1)
            (func (export "chapaev_alloc") (param i32) (result i32) i32.const 0)
            (func (export "chapaev_decide") (param i32) (result i32) i32.const 0))"#;
        assert!(matches!(
            load(wrong).unwrap_err(),
            LoadError::WrongExport {
                name: "chapaev_decide",
                ..
            }
        ));
        let no_memory = r#"(module
            (func (export "chapaev_alloc") (param i32) (result i32) i32.const 0)
            (func (export "chapaev_decide") (param i32 i32) (result i64) i64.const 0))"#;
        assert!(matches!(
            load(no_memory).unwrap_err(),
            LoadError::MissingExport("memory")
        ));
    }
}
