#!/bin/bash
# The lab's browser test: `rtl lab` in headless Chromium (Debian's /usr/bin/chromium) driven by
# playwright-core (pinned in package-lock.json, installed under target/lab-browser/).
# usage: crates/cli/tests/browser/run.sh [SCREENSHOT_DIR]   (from anywhere; default target/lab-browser/shots)
# Installs chromium (apt) and node/npm and playwright-core (npm ci) if they are missing.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../../.." && pwd)
cd "$root"
work=target/lab-browser
shots=${1:-$work/shots}
mkdir -p "$work" "$shots"

# Only what is missing: a machine whose Node.js came from elsewhere (with its own npm) cannot take
# Debian's npm beside it.
missing=()
[ -x /usr/bin/chromium ] || missing+=(chromium)
command -v npm >/dev/null || missing+=(nodejs npm)
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing ${missing[*]} (apt)"
  apt-get update -qq && apt-get install -y -qq "${missing[@]}" >/dev/null
fi
# playwright-core at the version of the lockfile, under target/ (nothing installed in the repository)
if ! cmp -s "$here/package-lock.json" "$work/package-lock.json" || ! [ -d "$work/node_modules/playwright-core" ]; then
  cp "$here/package.json" "$here/package-lock.json" "$work/"
  (cd "$work" && timeout 300 npm ci --no-audit --no-fund --loglevel=error)
fi
cp "$here/lab.test.cjs" "$work/"

cargo build --release -q -p rtl
# A reference directory of its own holding the study's cached 128-wide reference, so the test writes
# nothing into book/src/figures and renders no reference.
refs=$(mktemp -d)
log=$refs/lab.log
cp book/src/figures/render-reference-cornell-128-*.pfm "$refs/"
target/release/rtl lab --port 0 --width 128 --reference-dir "$refs" >"$log" 2>&1 &
pid=$!
trap 'kill $pid 2>/dev/null; rm -rf "$refs"' EXIT
url=
for _ in $(seq 100); do
  url=$(grep -o 'http://127\.0\.0\.1:[0-9]*/' "$log" || true)
  [ -n "$url" ] && break
  sleep 0.1
done
[ -n "$url" ] || { echo "rtl lab printed no URL: $(cat "$log")"; exit 1; }
echo "rtl lab at $url; screenshots in $shots"
timeout 300 node "$work/lab.test.cjs" "$url" "$shots"
