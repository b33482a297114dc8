#!/usr/bin/env bash
# Builds the seed corpora of the fuzz targets into fuzz/corpus/<target>/, from the import test
# fixtures (tests/fixtures/import) and from short simulated walks (`pdr simulate --format …`),
# each seed cut to at most 64 KiB at a line end. Reproducible: the simulator is deterministic.
#   fuzz/seed.sh            (re)builds every corpus; files the fuzzer added are kept
#   PDR=path/to/pdr fuzz/seed.sh   the same with that pdr (a relative path is from the repository)
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$(pwd)
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$ROOT/target}"
# The simulator's pdr: $PDR when given (`./dev test` hands it the tests profile's, already built),
# else the release build.
if [ -z "${PDR:-}" ]; then
  cargo build --release --bin pdr -q
  PDR="$CARGO_TARGET_DIR/release/pdr"
fi
SIM=$(mktemp -d)
trap 'rm -rf "$SIM"' EXIT
for scenario in straight gnss-city; do
  for f in pdr-log sensor-logger sensor-logger-ios sensor-logger-json phyphox gnss-logger \
           get-sensor-data oxford ms-indoor xio plain-csv tyrex ubicomp13 weallwalk; do
    mkdir -p "$SIM/$scenario"
    "$PDR" simulate --scenario "$scenario" --format "$f" --out "$SIM/$scenario/$f" >/dev/null
  done
  "$PDR" simulate --scenario "$scenario" --format tyrex --platform ios --out "$SIM/$scenario/tyrex-ios" >/dev/null
  "$PDR" simulate --scenario "$scenario" --events "$SIM/$scenario/events.json" >/dev/null
  "$PDR" simulate --scenario "$scenario" --platform ios --events "$SIM/$scenario/events-ios.json" >/dev/null
done
python3 fuzz/seed.py "$SIM" fuzz/corpus
