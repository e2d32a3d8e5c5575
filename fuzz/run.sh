#!/usr/bin/env bash
# Runs each cargo-fuzz target in turn for SECONDS seconds (default 600), one job and one worker at a
# time, from the committed corpora; libFuzzer's log of each run is left in fuzz/logs/<target>.log.
# Usage (from the repository root): bash fuzz/run.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")"
secs=${1:-600}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene_file checkpoint tables)
mkdir -p logs
for t in "${targets[@]}"; do
  echo "== $t: $(date -u +%H:%M:%S) for ${secs}s"
  rm -f fuzz-0.log
  cargo +nightly fuzz run -O "$t" "corpus/$t" -- \
    -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -jobs=1 -workers=1 || echo "$t exited $?"
  mv -f fuzz-0.log "logs/$t.log" 2>/dev/null || true
  echo "== $t done $(date -u +%H:%M:%S)"
  tail -n 5 "logs/$t.log" || true
done
