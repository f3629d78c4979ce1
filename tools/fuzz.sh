#!/usr/bin/env bash
# Coverage-guided fuzzing with AFL++ through afl.rs (`cargo afl`), on the stable
# toolchain: installs cargo-afl and builds AFL++ if they are missing, builds the
# instrumented targets of fuzz/, writes their seeds and dictionaries, and runs each
# target in turn for SECONDS (AFL++'s own `-V`). A crash or a hang fails the run, and
# its input is copied to tests/fuzz/regressions/TARGET/, where `cargo test --test fuzz`
# replays it.
#
#   tools/fuzz.sh [SECONDS] [TARGET...]     (default 60 s each, every target)
#
# Work files go to fuzz/target/afl/ (ILMR_AFL_DIR to change): seeds/, and out/TARGET/
# with AFL++'s queue and fuzzer_stats. One target at a time, niced: the machine is
# shared.
set -euo pipefail
cd "$(dirname "$0")/.."

# afl.rs's runtime is built per version of cargo-afl; the afl crate in fuzz/Cargo.lock
# is the same version.
afl_version=0.18.2
seconds=${1:-60}
shift || true
work=${ILMR_AFL_DIR:-fuzz/target/afl}

if ! [[ $seconds =~ ^[1-9][0-9]*$ ]]; then
    echo "usage: tools/fuzz.sh [SECONDS] [TARGET...]" >&2
    exit 2
fi

if ! cargo afl --version 2>/dev/null | grep -q "$afl_version"; then
    cargo install --locked --force cargo-afl --version "$afl_version"
fi
# `cargo afl fuzz` finds afl-fuzz only once AFL++ is built for this rustc (its help
# exits 1 either way).
if ! (cargo afl fuzz -h 2>&1 || true) | grep -q 'afl-fuzz++'; then
    cargo afl config --build --force
fi

(cd fuzz && nice -n 10 cargo afl build --release --locked)
bin=fuzz/target/release

rm -rf "$work/seeds"
"$bin/seeds" "$work/seeds"
if (($# == 0)); then
    # Every target the seeds were written for: the seeds binary holds the list.
    set -- $(cd "$work/seeds" && ls -d */ | tr -d /)
fi

# AFL++ here: no CPU governor to read, cores shared with other work, and a
# core_pattern this script may not change. Inputs past 2 s or 2 GB are findings.
export AFL_SKIP_CPUFREQ=1 AFL_NO_AFFINITY=1 AFL_I_DONT_CARE_ABOUT_MISSING_CRASHES=1
export AFL_NO_UI=1 AFL_QUIET=1
timeout_ms=2000
memory_mb=2048

failed=()
passed=0
for target in "$@"; do
    out="$work/out/$target"
    rm -rf "$out"
    mkdir -p "$out"
    echo "fuzz $target: $seconds s"
    nice -n 10 cargo afl fuzz -i "$work/seeds/$target" -o "$out" -x "$work/seeds/$target.dict" \
        -V "$seconds" -t "$timeout_ms" -m "$memory_mb" -- "$bin/$target" >"$out/afl.log" 2>&1 \
        || { tail -n 30 "$out/afl.log" >&2; failed+=("$target (afl-fuzz failed)"); continue; }
    stats="$out/default/fuzzer_stats"
    stat() { sed -n "s/^$1 *: *//p" "$stats"; }
    echo "fuzz $target: $(stat run_time) s, $(stat execs_done) execs, $(stat corpus_count) in queue," \
        "$(stat edges_found)/$(stat total_edges) edges ($(stat bitmap_cvg)), $(stat saved_crashes) crashes, $(stat saved_hangs) hangs"
    found=0
    for found_as in crashes:crash hangs:hang; do
        kind=${found_as#*:}
        for input in "$out/default/${found_as%:*}"/id:*; do
            [[ -e $input ]] || continue
            regressions="tests/fuzz/regressions/$target"
            mkdir -p "$regressions"
            name="afl-$kind-$(sha256sum "$input" | cut -c1-12)"
            cp "$input" "$regressions/$name"
            echo "fuzz $target: $kind saved as $regressions/$name" >&2
            found=$((found + 1))
        done
    done
    if ((found > 0)); then
        failed+=("$target ($found inputs)")
    else
        passed=$((passed + 1))
    fi
done

echo "fuzz: $passed passed, ${#failed[@]} failed"
if ((${#failed[@]} > 0)); then
    printf 'failed: %s\n' "${failed[@]}" >&2
    exit 1
fi
