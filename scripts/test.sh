#!/usr/bin/env bash
# The one command that runs every test of holey: formatting, lints, and
# the whole workspace's tests. CI (.ci/run) calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== cargo fmt --check"
cargo fmt --all -- --check

echo "== cargo clippy (all targets, -D warnings)"
cargo clippy --workspace --all-targets --locked -- -D warnings

shared="$(cd .. && pwd)/shared/data/meshes"
if [ -n "${HOLEY_SHARED_MESHES:-}" ]; then shared="$HOLEY_SHARED_MESHES"; fi
if [ -d "$shared" ]; then
    echo "== shared meshes: $shared"
else
    echo "== NOTE: $shared is absent: the tests that read real meshes will print SKIP"
fi

echo "== cargo test (release: the geometry tests are heavy)"
# --show-output makes the SKIP lines of tests that skip visible.
cargo test --workspace --release --locked -- --show-output

echo "== Python package (pip install . into a fresh virtualenv, then pytest)"
# Proves the install step a user takes: maturin (fetched by pip's build
# isolation) builds the abi3 extension from crates/python, and the suite
# in python/tests runs against the installed package, not the source tree.
venv="$(pwd)/target/python-venv"
rm -rf "$venv"
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet ".[test]"
(cd python/tests && "$venv/bin/python" -m pytest -q -rs -p no:cacheprovider)

echo "== browser tests (web/: npm ci, vite build, Chromium via playwright-core)"
# The front end is built from npm packages (three, vite, playwright-core)
# and tested in Debian's Chromium against the holey binary just built.
# Screenshots and timings land in web/e2e/artifacts/.
npm --prefix web ci --no-audit --no-fund
npm --prefix web run build
cargo build --release --locked -p holey-cli
HOLEY_BIN="$(pwd)/target/release/holey" node web/e2e/run.mjs

echo "== all tests passed"
