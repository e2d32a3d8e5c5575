#!/bin/bash
# The renderer on other processors than this one, emulated: QEMU's user-mode emulator
# (`qemu-x86_64 -cpu MODEL`, Debian's qemu-user; its TCG runs AVX2 since QEMU 7.2, not AVX-512)
# presents the CPUID of an Intel Haswell, an AMD Zen 2 and Zen 3 (AVX2, no AVX-512), and an Intel
# Westmere (no AVX at all) to the release binary. For each it checks that
#   - the run-time detection picks the tier that processor runs (`--explain`: avx2, or portable and
#     one path at a time), and refuses a tier it does not run with a clear error, not SIGILL;
#   - every render is the same bit for bit (linear PFM) as this machine's render with that tier
#     forced by `--hit-tier`: no AVX-512 instruction leaks into the AVX2 code, none of AVX into the
#     portable code, and no decision depends on the vendor where it should not.
# Emulation says nothing of speed: the targets of issue 16 are measured with `rtl bench targets` on
# real hardware. A negative control checks that the comparison does see a different image.
# usage: crates/cli/tests/emulated/run.sh   (from anywhere; installs qemu-user with apt if missing)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../../.." && pwd)
cd "$root"

if ! command -v qemu-x86_64 >/dev/null; then
  echo "installing qemu-user (apt)"
  apt-get update -qq && apt-get install -y -qq qemu-user >/dev/null
fi
# AVX2 in QEMU's TCG came with 7.2: an older emulator would stop the AVX2 processors' renders
version=$(qemu-x86_64 --version | sed -n 's/.*version \([0-9]*\)\.\([0-9]*\).*/\1 \2/p' | head -1)
read -r major minor <<<"$version"
if [ -z "$major" ] || [ "$major" -lt 7 ] || { [ "$major" = 7 ] && [ "$minor" -lt 2 ]; }; then
  echo "FAIL: qemu-x86_64 is older than 7.2 ('$(qemu-x86_64 --version | head -1)'): its TCG has no AVX2"
  exit 1
fi
cargo build --release -q -p rtl
rtl=$root/target/release/rtl
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# the processors: QEMU model, what it is, the tier it must get
cpus=(
  "Haswell|Intel Haswell (AVX2, no AVX-512)|avx2"
  "EPYC-Rome|AMD Zen 2 (AVX2)|avx2"
  "EPYC-Milan|AMD Zen 3 (AVX2)|avx2"
  "Westmere|Intel Westmere (no AVX)|portable"
)
# the renders: name and arguments (tiny images: the emulator runs some 50x slower than the machine)
cases=(
  "cornell-mixture|cornell --strategy mixture --width 64 --spp 8"
  "cornell-mis|cornell --strategy mis --width 64 --spp 8"
  "cornell-cosine|cornell --strategy cosine --width 32 --spp 4"
  "cornell-light|cornell --strategy light --width 32 --spp 4"
  "cornell-smoke|cornell-smoke --width 32 --spp 4"
  "simple-light|simple-light --width 32 --spp 4"
  "book2-final|book2-final --width 48 --spp 2"
  "book1-final|book1-final --width 32 --spp 2"
)

failed=0
fail() {
  echo "FAIL: $*"
  failed=1
}
quiet() { grep -v "^qemu-x86_64: warning:" || true; }

# this machine's render of each case with a forced tier, made once per tier: prints its file, or
# fails with rtl's last words
native() { # case-name args tier
  local out=$work/native-$1-$3.pfm
  if [ ! -f "$out" ]; then
    # shellcheck disable=SC2086
    if ! "$rtl" render $2 --threads 1 --hit-tier "$3" -o "$work/n.png" --linear "$out" \
      >"$work/native.log" 2>&1; then
      echo "the native render of $1 with --hit-tier $3 failed: $(tail -2 "$work/native.log")" >&2
      return 1
    fi
  fi
  echo "$out"
}

for cpu in "${cpus[@]}"; do
  IFS='|' read -r model what tier <<<"$cpu"
  echo "== $model: $what, expects the $tier tier"
  if ! explain=$(qemu-x86_64 -cpu "$model" "$rtl" render cornell --width 8 --spp 1 --explain 2>&1); then
    fail "$model: rtl render --explain failed: $(quiet <<<"$explain" | tail -2)"
    continue
  fi
  line=$(grep "^  intersection" <<<"$explain" || true)
  paths=$(grep "^  paths" <<<"$explain" || true)
  case $tier in
    avx2)
      grep -q ": AVX2 " <<<"$line" || fail "$model: --explain says '$line', not the AVX2 tier"
      grep -q "side by side in the vector lanes (avx2)" <<<"$paths" ||
        fail "$model: --explain says '$paths', not the lanes in AVX2"
      ;;
    portable)
      grep -q ": portable" <<<"$line" || fail "$model: --explain says '$line', not portable"
      grep -q ": one at a time" <<<"$paths" || fail "$model: --explain says '$paths', not one path at a time"
      ;;
  esac
  # a tier above its best is refused in words (exit 2), not run into an illegal instruction
  above=avx512
  [ "$tier" = portable ] && above=avx2
  set +e
  msg=$(qemu-x86_64 -cpu "$model" "$rtl" render cornell --width 8 --spp 1 --hit-tier $above -o "$work/x.png" 2>&1 | quiet)
  rc=${PIPESTATUS[0]}
  set -e
  if [ "$rc" != 2 ] || ! grep -q "does not run the $above tier" <<<"$msg"; then
    fail "$model: --hit-tier $above gave exit $rc: $msg"
  fi
  # `--hit-tier auto` with no AVX-512 has nothing to race, and says which tier runs instead
  # (a failed render is reported by the check below, not by `set -e` without a word)
  msg=$(qemu-x86_64 -cpu "$model" "$rtl" render cornell --width 8 --spp 1 --hit-tier auto -o "$work/x.png" 2>&1 | quiet) || true
  grep -q "note: --hit-tier auto: .* no race to time; $tier runs" <<<"$msg" ||
    fail "$model: --hit-tier auto did not say that $tier runs without a race: $msg"
  for c in "${cases[@]}"; do
    IFS='|' read -r name args <<<"$c"
    ref=$(native "$name" "$args" "$tier") || {
      fail "$model $name: no render of this machine's to compare with"
      continue
    }
    out=$work/$model-$name.pfm
    start=$EPOCHREALTIME
    # shellcheck disable=SC2086
    if ! qemu-x86_64 -cpu "$model" "$rtl" render $args --threads 1 -o "$work/q.png" --linear "$out" \
      2>&1 | quiet >"$work/log"; then
      fail "$model $name: the render failed: $(tail -2 "$work/log")"
      continue
    fi
    secs=$(awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { print b - a }')
    if cmp -s "$ref" "$out"; then
      printf '  %-16s same bit for bit as --hit-tier %s here (%.1f s emulated)\n' "$name" "$tier" "$secs"
    else
      fail "$model $name: differs from this machine's --hit-tier $tier render"
    fi
  done
done

# the negative control: a render of another seed must not pass the comparison
"$rtl" render cornell --strategy mixture --width 64 --spp 8 --threads 1 --seed 2 \
  -o "$work/n.png" --linear "$work/seed2.pfm" >/dev/null 2>&1
seed1=$(native cornell-mixture "cornell --strategy mixture --width 64 --spp 8" avx2)
if cmp -s "$seed1" "$work/seed2.pfm"; then
  fail "the comparison does not tell seed 1's image from seed 2's"
else
  echo "negative control: seed 2's image differs from seed 1's, as the comparison must see"
fi

[ $failed = 0 ] || exit 1
echo "emulated processors: all renders the same bit for bit, each with its own tier"
