#!/usr/bin/env bash
# Drives the built server with headless Neovim (Debian's 0.7.2 works) as the client.
# Usage: lsp/tests/nvim/run.sh   (from anywhere; builds ilmr-lsp first)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../../.." && pwd)"
command -v nvim >/dev/null || { echo "nvim not found (apt-get install neovim)"; exit 2; }
# ilmrc too: the "run in simulator" lens runs the one beside the server.
cargo build -q -p ilmr-lsp -p ilmrc --manifest-path "$repo/Cargo.toml"
ws="$(mktemp -d)"
trap 'rm -rf "$ws"' EXIT
printf '%s\n' 'käännös = turn(left)' 'wait(käännös)' 'kääntö = followwall(lft)' 't = turn(' 'KIERROS' > "$ws/task.ilmr"
printf '%s\n' 'KIERROS:' 'speed(0.3)' > "$ws/skills.ilms"
printf '%s\n' 'm = goahead(0.5)' 'turn(d=20,c=0.5)' 'wait(m)' 'speed(0.3)' '' \
  'f = followwall(left,1)' 'break(followw)' > "$ws/lens.ilmr"
# A test file of lens.ilmr with a misspelt key and two assertions being typed.
printf '%s\n' 'task = "lens.ilmr"' 'seed = 1' '' '[[test]]' 'name = "lens"' \
  'assert = ["eventually: line ", "ev"]' > "$ws/lens.test.toml"
printf '%s\n' 'followwall(left)' '' 'd = sensor(battery)' 'if(d < 10)' 'priority = highest' \
  'speed(0)' 'endif' '' 'break' > "$ws/enders.ilmr"
ILMR_LSP="$repo/target/debug/ilmr-lsp" ILMR_WS="$ws" \
  timeout 120 nvim --headless --clean -u NONE -S "$here/e2e.lua"
