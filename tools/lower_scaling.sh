#!/bin/sh
# `ilmrc check` against `ilmrc build` of the counting-blocks task (issue 14) at 10,000
# and 100,000 blocks, through the real binary, fastest of five runs each (wall time);
# then 10,000 to 1,000,000 blocks in process (a task of 1,000,000 blocks is 71 MB,
# past the 8 MiB `ilmrc` reads). Figures in docs/performance.md.
#
#   cargo build --release -p ilmrc && tools/lower_scaling.sh
set -eu
ILMRC=${ILMRC:-./target/release/ilmrc}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fastest() {
    best=
    for _ in 1 2 3 4 5; do
        start=$(date +%s%N)
        "$@" >/dev/null
        end=$(date +%s%N)
        t=$(( (end - start) / 1000 ))
        if [ -z "$best" ] || [ "$t" -lt "$best" ]; then best=$t; fi
    done
    echo "$best"
}
echo "| blocks | source bytes | ilmrc check | ilmrc build | build / check | .ilmb bytes |"
echo "| ---: | ---: | ---: | ---: | ---: | ---: |"
for n in 10000 100000; do
    cargo run -q --release -p ilmr-compiler --example blocks "$n" >"$tmp/t.ilmr"
    check=$(fastest "$ILMRC" check "$tmp/t.ilmr")
    build=$(fastest "$ILMRC" build -o "$tmp/t.ilmb" "$tmp/t.ilmr")
    ratio=$(echo "scale=2; $build / $check" | bc)
    printf '| %s | %s | %s.%s ms | %s.%s ms | %s | %s |\n' "$n" "$(wc -c <"$tmp/t.ilmr")" \
        $((check / 1000)) $((check % 1000 / 100)) $((build / 1000)) $((build % 1000 / 100)) \
        "$ratio" "$(wc -c <"$tmp/t.ilmb")"
done
echo
cargo run -q --release -p ilmr-compiler --example build_cost 10000 100000 1000000
