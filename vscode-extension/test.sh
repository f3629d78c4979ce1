#!/usr/bin/env bash
# Installs the locked dependencies, runs the grammar tests and the lens tests against
# the built ilmr-lsp (tests/lens.test.mjs), and builds the .vsix. Needs node 20, npm
# and cargo (for the server and the ilmrc its run lens starts); run from anywhere.
set -euo pipefail
cd "$(dirname "$0")"
npm ci --no-audit --no-fund
npm run test:grammar
if [ -z "${ILMR_LSP:-}" ]; then
    cargo build -q -p ilmr-lsp -p ilmrc --manifest-path ../Cargo.toml
fi
npm run test:lens
npm run package
test -s ilmr.vsix
echo "vscode-extension: grammar tests passed, ilmr.vsix built"
