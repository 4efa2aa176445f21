#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ with clang in a build folder of their own, then runs
# each over its seed corpus for a short while. The CTest entry `fuzz.targets` runs it; by hand:
#
#   fuzz/run_fuzzers.sh BUILD_DIR [SECONDS_PER_TARGET]      (default 8 s)
#
# A fixed libFuzzer seed makes a run repeatable: a failure in CI is the same failure here.
# Exits 77, which CTest reports as skipped, when clang++ or its libFuzzer runtime is missing:
# a machine that cannot fuzz must not report fuzzing as passed.
set -euo pipefail

src=$(cd "$(dirname "$0")" && pwd)
build=${1:?usage: run_fuzzers.sh BUILD_DIR [SECONDS_PER_TARGET]}
seconds=${2:-8}
cxx=${SKYFUSE_FUZZ_CXX:-clang++}

skip() {
  echo "fuzz: skipped: $1 (Debian: apt-get install clang libclang-rt-14-dev)"
  exit 77
}

command -v "$cxx" >/dev/null || skip "$cxx not found"
mkdir -p "$build/probe"
probe=$build/probe/probe
echo 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }' \
  >"$probe.cpp"
"$cxx" -fsanitize=fuzzer,address,undefined "$probe.cpp" -o "$probe" 2>"$probe.log" ||
  skip "$cxx cannot link libFuzzer with ASan and UBSan: $(head -c 300 "$probe.log")"

start=$SECONDS
cmake -S "$src" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" >/dev/null
cmake --build "$build" --parallel 2
echo "fuzz: built in $((SECONDS - start)) s"

# run TARGET [libFuzzer options...]: new inputs go to a scratch corpus (never into the source
# tree), a finding to findings/, and -timeout makes a 10 s input a finding (a hang).
run() {
  local target=$1
  shift
  local corpus=$build/corpus/$target
  rm -rf "$corpus"
  mkdir -p "$corpus" "$build/findings"
  if ! "$build/fuzz_$target" -seed=1 -max_total_time="$seconds" -timeout=10 \
    -print_final_stats=1 -artifact_prefix="$build/findings/$target-" "$@" \
    "$corpus" "$src/corpus/$target" >"$build/$target.log" 2>&1; then
    tail -n 60 "$build/$target.log"
    local input
    input=$(ls -t "$build/findings/$target-"* 2>/dev/null | head -n 1)
    echo "fuzz: $target: FINDING; replay it with: $build/fuzz_$target ${input:-<input>}"
    return 1
  fi
  local runs rate
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$build/$target.log")
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$build/$target.log")
  echo "fuzz: $target: $runs runs, $rate exec/s, no finding"
}

status=0
run scenario_loader || status=1
run increment_check -dict="$src/doubles.dict" -max_len=433 || status=1
run observation_check -dict="$src/doubles.dict" -max_len=96 || status=1
# A UDP datagram of ASTERIX is at most 65 507 octets; 4 096 holds many blocks and records.
run asterix_decode -max_len=4096 || status=1
exit $status
