//! Embeds what a per-model build needs into the compiler module, so an
//! installed package works without the clone it was built from:
//!
//! - the runtime crate (`autosim-runtime`: `src/` and a standalone
//!   manifest, its workspace-inherited fields resolved) and the generic
//!   wrapper crate (`autosim-python-model`), as `(relative path, text)`
//!   pairs in `SOURCES`, laid out as `<crate name>/...` (path dependencies
//!   between them rewritten to siblings);
//! - `FINGERPRINT`: a hash of those files and of the compiler's own sources
//!   (`autosim-core/src`, `rust/compiler`), part of every model's cache key
//!   so that a changed compiler or runtime rebuilds cached models.

use std::collections::hash_map::DefaultHasher;
use std::fmt::Write as _;
use std::hash::{Hash, Hasher};
use std::path::{Path, PathBuf};

fn main() {
    let here = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").expect("cargo sets it"));
    let root = here.join("..");
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("cargo sets it"));
    let workspace = read_table(&root.join("Cargo.toml"));
    let crates = [
        ("autosim-runtime", root.join("autosim-runtime")),
        ("autosim-python-model", here.join("model-wrapper")),
    ];
    let mut entries: Vec<(String, PathBuf)> = Vec::new();
    let mut hasher = DefaultHasher::new();
    for (name, dir) in &crates {
        let manifest = standalone_manifest(&dir.join("Cargo.toml"), &workspace);
        let manifest_path = out.join(format!("{name}.Cargo.toml"));
        std::fs::write(&manifest_path, &manifest).expect("OUT_DIR is writable");
        manifest.hash(&mut hasher);
        entries.push((format!("{name}/Cargo.toml"), manifest_path));
        for file in rust_files(&dir.join("src")) {
            let relative = file
                .strip_prefix(dir)
                .expect("under the crate")
                .to_path_buf();
            entries.push((format!("{name}/{}", slashed(&relative)), file));
        }
        println!("cargo::rerun-if-changed={}", dir.display());
    }
    for (path, file) in &entries {
        path.hash(&mut hasher);
        std::fs::read(file).expect("readable").hash(&mut hasher);
    }
    for dir in [root.join("autosim-core/src"), here.join("rust")] {
        println!("cargo::rerun-if-changed={}", dir.display());
        for file in rust_files(&dir) {
            std::fs::read(&file).expect("readable").hash(&mut hasher);
        }
    }
    let mut code = String::from(
        "/// The Rust sources of a per-model build.\npub static SOURCES: &[(&str, &str)] = &[\n",
    );
    for (path, file) in &entries {
        let _ = writeln!(
            code,
            "    ({path:?}, include_str!({:?})),",
            file.display().to_string()
        );
    }
    code.push_str("];\n");
    let _ = writeln!(
        code,
        "/// Hash of the compiler, runtime and wrapper sources.\npub const FINGERPRINT: &str = \"{:016x}\";",
        hasher.finish()
    );
    std::fs::write(out.join("sources.rs"), code).expect("OUT_DIR is writable");
}

fn read_table(path: &Path) -> toml::Table {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    text.parse()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Every `.rs` file under `dir`, sorted (so the fingerprint is stable).
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let listing = std::fs::read_dir(&d).unwrap_or_else(|e| panic!("{}: {e}", d.display()));
        for entry in listing.flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

fn slashed(path: &Path) -> String {
    let parts: Vec<String> = path
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    parts.join("/")
}

/// The crate's manifest with every `workspace = true` replaced by the
/// workspace's value, path dependencies pointing at sibling folders named
/// after the dependency, and no dev-dependencies, benches, tests or
/// examples (a per-model build compiles the library alone).
fn standalone_manifest(path: &Path, workspace: &toml::Table) -> String {
    let mut manifest = read_table(path);
    let empty = toml::Table::new();
    let ws = workspace
        .get("workspace")
        .and_then(|w| w.as_table())
        .unwrap_or(&empty);
    let ws_package = ws
        .get("package")
        .and_then(|p| p.as_table())
        .unwrap_or(&empty);
    let ws_deps = ws
        .get("dependencies")
        .and_then(|p| p.as_table())
        .unwrap_or(&empty);
    for section in [
        "dev-dependencies",
        "bench",
        "test",
        "example",
        "workspace",
        "lints",
    ] {
        manifest.remove(section);
    }
    if let Some(toml::Value::Table(package)) = manifest.get_mut("package") {
        let keys: Vec<String> = package.keys().cloned().collect();
        for key in keys {
            if inherits(&package[&key]) {
                let value = ws_package
                    .get(&key)
                    .cloned()
                    .unwrap_or_else(|| panic!("workspace.package.{key}"));
                package.insert(key, value);
            }
        }
        for auto in ["autobenches", "autotests", "autoexamples", "autobins"] {
            package.insert(auto.into(), toml::Value::Boolean(false));
        }
        package.remove("build");
    }
    if let Some(toml::Value::Table(deps)) = manifest.get_mut("dependencies") {
        let names: Vec<String> = deps.keys().cloned().collect();
        for name in names {
            let resolved = resolve_dependency(&name, &deps[&name], ws_deps);
            deps.insert(name, resolved);
        }
    }
    toml::to_string(&manifest).expect("a manifest serializes")
}

fn inherits(value: &toml::Value) -> bool {
    value
        .as_table()
        .and_then(|t| t.get("workspace"))
        .and_then(|w| w.as_bool())
        == Some(true)
}

fn resolve_dependency(name: &str, value: &toml::Value, ws_deps: &toml::Table) -> toml::Value {
    let mut table = match value {
        toml::Value::String(version) => {
            let mut t = toml::Table::new();
            t.insert("version".into(), toml::Value::String(version.clone()));
            t
        }
        toml::Value::Table(t) => t.clone(),
        other => panic!("dependency {name}: {other:?}"),
    };
    if inherits(value) {
        table.remove("workspace");
        let base = match ws_deps.get(name) {
            Some(toml::Value::String(version)) => {
                let mut t = toml::Table::new();
                t.insert("version".into(), toml::Value::String(version.clone()));
                t
            }
            Some(toml::Value::Table(t)) => t.clone(),
            _ => panic!("workspace.dependencies.{name}"),
        };
        let features: Vec<toml::Value> = base
            .get("features")
            .and_then(|f| f.as_array())
            .into_iter()
            .flatten()
            .chain(
                table
                    .get("features")
                    .and_then(|f| f.as_array())
                    .into_iter()
                    .flatten(),
            )
            .cloned()
            .collect();
        let mut merged = base;
        for (k, v) in table {
            merged.insert(k, v);
        }
        if !features.is_empty() {
            merged.insert("features".into(), toml::Value::Array(features));
        }
        table = merged;
    }
    if table.contains_key("path") {
        table.insert("path".into(), toml::Value::String(format!("../{name}")));
    }
    toml::Value::Table(table)
}
