#!/usr/bin/env bash
# The one command that runs every test of holey: formatting, lints, and
# the whole workspace's tests. CI (.ci/run) calls exactly this.
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== cargo fmt --check"
cargo fmt --all -- --check

echo "== cargo clippy (all targets, -D warnings)"
cargo clippy --workspace --all-targets --locked -- -D warnings

echo "== cargo test (release: the geometry tests are heavy)"
cargo test --workspace --release --locked

echo "== all tests passed"
