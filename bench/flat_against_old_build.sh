#!/usr/bin/env bash
# The flat exchange of this checkout's build against an older checkout's, run alternately in one
# sitting (docs/performance.md, "The flat exchange against the build before the tree").
#   bench/flat_against_old_build.sh OLD_CHECKOUT [NEW_CHECKOUT]
# Each checkout must be built (build/bin/skyfuse). A build from before the tree exchange has no
# --exchange option: its runs are flat. Prints one line per run: build, M, rounds/s, p50 latency.
set -euo pipefail
old=$(cd "$1" && pwd)
new=$(cd "${2:-$(dirname "$0")/..}" && pwd)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# --exchange flat where the build knows the option (asked once per checkout).
exchange_of() { "$1/build/bin/skyfuse" run --help | grep -q -- --exchange && echo "--exchange flat" || true; }
declare -A exchange=([$old]=$(exchange_of "$old") [$new]=$(exchange_of "$new"))

run() {  # checkout label stations steps [options...]
  local tree=$1 label=$2 m=$3 steps=$4
  shift 4
  # shellcheck disable=SC2086  # empty or two words
  "$tree/build/bin/skyfuse" run --scenario "$tree/scenarios/ring64.yaml" --stations "$m" \
    --steps "$steps" ${exchange[$tree]} "$@" --out "$out/$label" 2>&1 |
    awk -v b="$label" -v m="$m" -v x="$*" '
      /rounds per second/ { r = $4 } /latency/ { l = $4 } /in time/ { t = $(NF - 1) }
      END { printf "%s M=%s %s rounds/s %s p50_us %s%s\n", b, m, x, r, l, t == "" ? "" : " in_time_% " t }'
}

for pair in 1 2 3; do
  for m_steps in "4 3000" "8 2000" "16 1000" "32 300"; do
    read -r m steps <<<"$m_steps"
    run "$old" old "$m" "$steps"
    run "$new" new "$m" "$steps"
  done
done
for pair in 1 2; do
  for m in 16 24; do
    run "$old" old "$m" 500 --realtime-deadline-ms 15
    run "$new" new "$m" 500 --realtime-deadline-ms 15
  done
done
