#!/usr/bin/env bash
# Every test of the repository: the Rust workspace (unit, integration, snapshot and
# property tests; the ROS 2 ones in network namespaces of their own, which needs root
# or CAP_SYS_ADMIN, `unshare` and `ip`), the language server driven by headless Neovim,
# and the VS Code extension (grammar tests and packaging).
set -euo pipefail
cd "$(dirname "$0")/.."

# Software this project did not write, which the interop tests run against: Eclipse
# Cyclone DDS's Python binding (it ships its own C library), Foxglove's MCAP readers, and
# a JSON Schema validator for the traces (docs/trace-schema.json).
python_packages="cyclonedds mcap mcap-protobuf-support mcap-ros2-support jsonschema"
if ! python3 -c 'import cyclonedds.idl, mcap.reader, mcap_protobuf.decoder, mcap_ros2.decoder, jsonschema' >/dev/null 2>&1; then
    python3 -m pip install --quiet --disable-pip-version-check $python_packages \
        || python3 -m pip install --quiet --disable-pip-version-check --break-system-packages $python_packages
fi
python3 -c 'import cyclonedds.idl, mcap.reader, mcap_protobuf.decoder, mcap_ros2.decoder, jsonschema'

# The fuzz crate is a workspace of its own whose lock file CI uses as it is; it goes
# stale when a crate it builds gains a dependency. Said here, before an hour of CI.
if ! (cd fuzz && cargo metadata --locked --format-version 1 >/dev/null 2>&1); then
    echo "fuzz/Cargo.lock is stale: run \`(cd fuzz && cargo metadata --format-version 1 >/dev/null)\` and commit it" >&2
    exit 1
fi

# Foxglove's own WebSocket client, which watches a live run (tests/foxglove_live.rs).
(cd tests/foxglove && npm ci --no-audit --no-fund --silent)

cargo test --workspace

# The language server with a real editor as its client: headless Neovim.
bash lsp/tests/nvim/run.sh

if command -v npm >/dev/null 2>&1; then
    bash vscode-extension/test.sh
else
    echo "npm not found: the VS Code extension's tests need node 20 and npm" >&2
    exit 1
fi
