//! Embeds the built browser front end (`web/dist`) in the server, so that
//! `holey serve` works from any directory, after `cargo install`, and when
//! the binary is copied elsewhere.
//!
//! When the front end is missing or older than its sources (`web/src`,
//! `web/index.html`, the npm manifests, the Vite configuration), this
//! script builds it with npm first (`npm ci` when `node_modules` is
//! missing or older than the lock file, then `npm run build`). Without
//! npm, or with `HOLEY_NO_WEB_BUILD` set, nothing is built: whatever
//! `web/dist` holds is embedded (possibly nothing, in which case the
//! server explains how to build it), and a warning says so.
//!
//! The output is `$OUT_DIR/embedded_web.rs`: a table of the files'
//! paths relative to `web/dist` and their bytes (`include_bytes!`), which
//! also makes cargo rebuild the crate when a built file changes.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::SystemTime;

fn main() {
    let manifest = PathBuf::from(std::env::var_os("CARGO_MANIFEST_DIR").unwrap_or_default());
    let web = manifest.join("../../web");
    let out = PathBuf::from(std::env::var_os("OUT_DIR").unwrap_or_default());
    println!("cargo:rerun-if-env-changed=HOLEY_NO_WEB_BUILD");
    let dist = web.join("dist");
    if web.join("package.json").is_file() {
        for input in [
            "src",
            "index.html",
            "package.json",
            "package-lock.json",
            "vite.config.js",
            "dist",
        ] {
            println!("cargo:rerun-if-changed={}", web.join(input).display());
        }
        if let Err(why) = build_if_stale(&web) {
            println!("cargo:warning=the browser front end was not rebuilt: {why}");
        }
    }
    let mut files = Vec::new();
    if dist.join("index.html").is_file() {
        collect(&dist, &dist, &mut files);
    } else {
        println!(
            "cargo:warning=web/dist is not built: `holey serve` will explain how to build the front end"
        );
    }
    files.sort();
    let mut table = String::from(
        "/// The built front end: paths relative to `web/dist`, and bytes.\n\
         pub static FILES: &[(&str, &[u8])] = &[\n",
    );
    for (relative, absolute) in &files {
        table += &format!("    ({relative:?}, include_bytes!({absolute:?})),\n");
    }
    table += "];\n";
    if let Err(e) = fs::write(out.join("embedded_web.rs"), table) {
        panic!("cannot write the embedded front end's table: {e}");
    }
}

/// Rebuilds `web/dist` with npm when it is missing or older than its
/// sources.
fn build_if_stale(web: &Path) -> Result<(), String> {
    let sources = [
        "src",
        "index.html",
        "package.json",
        "package-lock.json",
        "vite.config.js",
    ];
    let newest_source = sources.iter().filter_map(|s| newest(&web.join(s))).max();
    let built = modified(&web.join("dist/index.html"));
    let stale = match (built, newest_source) {
        (None, _) => true,
        (Some(b), Some(s)) => s > b,
        (Some(_), None) => false,
    };
    if !stale {
        return Ok(());
    }
    if std::env::var_os("HOLEY_NO_WEB_BUILD").is_some() {
        return Err("HOLEY_NO_WEB_BUILD is set".into());
    }
    let installed = modified(&web.join("node_modules/.package-lock.json"));
    let lock = modified(&web.join("package-lock.json"));
    if installed.is_none() || lock > installed {
        npm(web, &["ci", "--no-audit", "--no-fund"])?;
    }
    npm(web, &["run", "build"])
}

fn npm(web: &Path, args: &[&str]) -> Result<(), String> {
    let status = Command::new("npm")
        .arg("--prefix")
        .arg(web)
        .args(args)
        .stdout(std::process::Stdio::null())
        .status()
        .map_err(|e| format!("npm could not be started ({e}); install Node.js with npm"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("`npm {}` failed ({status})", args.join(" ")))
    }
}

fn modified(path: &Path) -> Option<SystemTime> {
    fs::metadata(path).and_then(|m| m.modified()).ok()
}

/// The newest modification time of a file, or of any file under a folder.
fn newest(path: &Path) -> Option<SystemTime> {
    let meta = fs::metadata(path).ok()?;
    if !meta.is_dir() {
        return meta.modified().ok();
    }
    fs::read_dir(path)
        .ok()?
        .filter_map(|entry| entry.ok())
        .filter_map(|entry| newest(&entry.path()))
        .max()
}

/// Every file under `dir`, as (path relative to `root` with `/`, absolute path).
fn collect(root: &Path, dir: &Path, files: &mut Vec<(String, String)>) {
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.filter_map(|e| e.ok()) {
        let path = entry.path();
        if path.is_dir() {
            collect(root, &path, files);
        } else if let (Ok(relative), Ok(absolute)) = (path.strip_prefix(root), path.canonicalize())
        {
            let relative = relative
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect::<Vec<_>>()
                .join("/");
            files.push((relative, absolute.to_string_lossy().into_owned()));
        }
    }
}
