#!/usr/bin/env bash
# Runs fuzz targets with the project's limits, one after the other:
#   fuzz/run.sh SECONDS TARGET...     e.g. fuzz/run.sh 600 live sniff
# Builds them (cargo +nightly fuzz build), seeds missing corpora (fuzz/seed.sh), and keeps
# fuzzing after a crash (fork mode), so a run always lasts SECONDS; crash, leak, timeout and
# out-of-memory inputs go to fuzz/artifacts/<target>/, the log to fuzz/logs/<target>.log, and
# the final line of each log gives the executions (#N), cov, ft and corpus size.
set -euo pipefail
cd "$(dirname "$0")"
secs=$1; shift
# The fuzz build's own target folder, never the main build's (FUZZ_TARGET_DIR to move it).
export CARGO_TARGET_DIR="${FUZZ_TARGET_DIR:-$(pwd)/target}"
cargo +nightly fuzz build >/dev/null
for t in "$@"; do
  [ -d "corpus/$t" ] || ./seed.sh
  mkdir -p "artifacts/$t" logs
  nice -n 19 "$CARGO_TARGET_DIR/$(rustc +nightly -vV | sed -n "s/host: //p")/release/$t" "corpus/$t" \
    -max_total_time="$secs" -max_len=65536 -rss_limit_mb=2048 -malloc_limit_mb=1024 -timeout=10 \
    -fork=1 -ignore_crashes=1 -artifact_prefix="artifacts/$t/" -print_final_stats=1 \
    >"logs/$t.log" 2>&1 || true
  echo "$t: $(grep -E '^#[0-9]+' "logs/$t.log" | tail -1)"
  ls "artifacts/$t" | sed 's/^/  /'
done
