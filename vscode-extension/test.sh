#!/usr/bin/env bash
# Installs the locked dependencies, runs the grammar tests and builds the .vsix.
# Needs node 20 and npm; run from anywhere.
set -euo pipefail
cd "$(dirname "$0")"
npm ci --no-audit --no-fund
npm run test:grammar
npm run package
test -s ilmr.vsix
echo "vscode-extension: grammar tests passed, ilmr.vsix built"
