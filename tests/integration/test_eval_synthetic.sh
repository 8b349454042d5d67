#!/usr/bin/env bash
# tools/nerv eval synthetic: renders the named synthetic sets once, scores each
# with bench_detection and prints one row per set.
#  - the held-out sets at 2 frames: four rows, each the figures bench_detection
#    itself prints for that folder;
#  - a second run renders nothing (the sets are cached by generator + preset);
#  - bench_detection's disparity cache is read back, per build, and pruned;
#  - bench_detection --visible ignores hidden objects without --max-distance too;
#  - --json holds the same figures;
#  - --true-disparity reaches bench_detection, and both tables say it is the rendered disparity;
#  - bad options end with one line naming them and exit 2.
# No LCM bus is involved (bench_detection runs the stages in-process).
source "$(dirname "$0")/lib.sh"

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
nerv() { NERV_BUILD="$NERV_BUILD" "$NERV_ROOT/tools/nerv" "$@"; }

nerv eval synthetic --sets heldout --frames 2 --out "$out/sets" >"$out/first.txt" 2>"$out/first.err" \
  || fail "eval synthetic exited with $?: $(tail -n 3 "$out/first.err")"
rows=$(grep -cE '^[a-z_0-9]+ +2 +[0-9.]+/[0-9.]+/[0-9.]+ +[0-9.]+/[0-9.]+/[0-9.]+ +[0-9]+ of [0-9]+$' "$out/first.txt" || true)
[[ "$rows" == 4 ]] || fail "expected 4 rows of figures, got $rows: $(cat "$out/first.txt")"
for name in urban_13 urban_14 wet_road_9 highway_31; do
  grep -q "^$name " "$out/first.txt" || fail "no row for $name"
done
[[ $(grep -c "rendering" "$out/first.err") == 4 ]] || fail "the first run should render four sets: $(cat "$out/first.err")"
pass "four held-out sets rendered and scored"

# The row is what bench_detection prints for that folder. (Three folders of other
# builds in its cache, the oldest to be pruned: checked below.)
mkdir -p "$out/cache/build-old1" "$out/cache/build-old2" "$out/cache/build-old3"
touch -d '3 days ago' "$out/cache/build-old1"; touch -d '2 days ago' "$out/cache/build-old2"
"$BIN/bench_detection" --data "$out/sets/urban_14_2" --max-distance 40 --visible --cache "$out/cache" \
  >"$out/bench.txt" 2>&1 || fail "bench_detection exited with $?"
want=$(awk '/^stixel \+ SNV/ {printf "%.3f/%.3f/%.3f", $(NF-2), $(NF-1), $NF}' "$out/bench.txt")
got=$(awk '$1 == "urban_14" {print $4}' "$out/first.txt")
[[ -n "$want" && "$got" == "$want" ]] || fail "urban_14 row says $got, bench_detection says $want"
pass "urban_14's row matches bench_detection ($got)"

# The disparity cache: this build's maps in a folder of their own, read back on the
# next run (nothing computed), and at most two other builds' folders kept.
"$BIN/bench_detection" --data "$out/sets/urban_14_2" --max-distance 40 --visible --cache "$out/cache" \
  >"$out/bench2.txt" 2>&1 || fail "bench_detection exited with $?"
grep -q 'nerv_sgm [0-9.]* / [0-9.]* (0 computed, rest cached)' "$out/bench2.txt" \
  || fail "the second run computed maps again: $(grep 'ms per frame' "$out/bench2.txt")"
cmp -s <(grep -v '^ms per frame' "$out/bench.txt") <(grep -v '^ms per frame' "$out/bench2.txt") \
  || fail "the cached run printed other figures"
[[ $(ls -d "$out"/cache/build-* | wc -l) == 3 && ! -e "$out/cache/build-old1" ]] \
  || fail "the cache should hold this build and the two newest others: $(ls "$out/cache")"
pass "the disparity cache is read back and keeps three builds"

# Hidden objects (--visible) are ignored with or without a distance limit.
objects() {
  "$BIN/bench_detection" --data "$out/sets/urban_13_2" --visible --cache "$out/cache" "$@" 2>&1 \
    | awk '/^stixel only/ {print $3}'
}
a=$(objects) b=$(objects --max-distance 1000)
[[ -n "$a" && "$a" == "$b" ]] || fail "--visible counts $a objects without a distance limit, $b with --max-distance 1000"
pass "--visible ignores hidden objects with or without --max-distance ($a objects)"

nerv eval synthetic --sets heldout --frames 2 --out "$out/sets" >"$out/second.txt" 2>"$out/second.err" \
  || fail "second run exited with $?"
! grep -q rendering "$out/second.err" || fail "the second run rendered again: $(cat "$out/second.err")"
cmp -s "$out/first.txt" "$out/second.txt" || fail "the second run printed other figures"
pass "second run reuses the rendered sets and prints the same figures"

nerv eval synthetic --sets heldout --frames 2 --out "$out/sets" --json >"$out/rows.json" 2>/dev/null \
  || fail "--json exited with $?"
[[ $(grep -o '"set":"' "$out/rows.json" | wc -l) == 4 ]] && grep -q '^{"disparity":"matcher",.*"sets":\[{"set":"urban_13","scene":"urban","seed":13,"frames":2,' "$out/rows.json" \
  || fail "--json does not hold the four sets: $(head -c 300 "$out/rows.json")"
f1=$(sed 's/{"set"/\n{"set"/g' "$out/rows.json" | grep '^{"set":"urban_14"' | grep -o '"stixel_snv":{[^}]*}' \
  | grep -o '"f1":[0-9.]*' | cut -d: -f2)
[[ -n "$f1" && "$got" == */"$f1" ]] || fail "urban_14's JSON F1 $f1 differs from its row $got"
pass "--json holds the same figures ($f1)"

nerv eval synthetic --sets heldout --frames 2 --out "$out/sets" --true-disparity >"$out/true.txt" 2>&1 \
  || fail "--true-disparity exited with $?"
grep -q "rendered disparity" "$out/sets/urban_13.txt" || fail "--true-disparity did not reach bench_detection"
grep -q "^disparity: the rendered disparity" "$out/true.txt" || fail "the oracle's table does not say it is one"
pass "--true-disparity reaches bench_detection"

expect_error() {  # expect_error PATTERN ARGS...
  local pattern=$1 rc=0
  shift
  nerv eval synthetic "$@" --out "$out/sets" >"$out/bad.txt" 2>&1 || rc=$?
  [[ $rc == 2 ]] || fail "eval synthetic $* exited with $rc, expected 2"
  [[ $(wc -l <"$out/bad.txt") == 1 ]] && grep -q "$pattern" "$out/bad.txt" \
    || fail "eval synthetic $*: expected one line naming '$pattern', got: $(cat "$out/bad.txt")"
}
expect_error "'bogus'" --sets bogus
expect_error "'0'" --frames 0
expect_error "'--frobnicate'" --frobnicate
pass "bad options end with one line and exit 2"
