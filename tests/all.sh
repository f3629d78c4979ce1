#!/usr/bin/env bash
# Every test of the repository: the Rust workspace (unit, integration, snapshot and
# property tests) and the VS Code extension (grammar tests and packaging).
set -euo pipefail
cd "$(dirname "$0")/.."

cargo test --workspace

if command -v npm >/dev/null 2>&1; then
    bash vscode-extension/test.sh
else
    echo "npm not found: the VS Code extension's tests need node 20 and npm" >&2
    exit 1
fi
