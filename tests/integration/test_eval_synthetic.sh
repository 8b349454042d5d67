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
#  - eval band: the same rows on gray requantized at another offset, cached apart, and
#    --compare's paired table;
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

expect_error() {  # expect_error synthetic|band PATTERN ARGS...
  local what=$1 pattern=$2 rc=0
  shift 2
  nerv eval "$what" "$@" --out "$out/sets" >"$out/bad.txt" 2>&1 || rc=$?
  [[ $rc == 2 ]] || fail "eval $what $* exited with $rc, expected 2"
  [[ $(wc -l <"$out/bad.txt") == 1 ]] && grep -q "$pattern" "$out/bad.txt" \
    || fail "eval $what $*: expected one line naming '$pattern', got: $(cat "$out/bad.txt")"
}
expect_error synthetic "'bogus'" --sets bogus
expect_error synthetic "'0'" --frames 0
expect_error synthetic "'--frobnicate'" --frobnicate
pass "bad options end with one line and exit 2"

# eval band: the same scores on gray requantized at other offsets. Its decoder
# column is the table above; each offset's maps are cached apart from the decoder's.
before=$(find "$out/sets/disparity_cache" -name '*.png' | wc -l)
nerv eval band --sets heldout --frames 2 --out "$out/sets" --offsets "0.5" --compare stixel.max_height_above_ground_m=1.5 \
  >"$out/band.txt" 2>"$out/band.err" || fail "eval band exited with $?: $(tail -n 3 "$out/band.err")"
after=$(find "$out/sets/disparity_cache" -name '*.png' | wc -l)
[[ $((after - before)) == 8 ]] || fail "offset 0.5 should add 8 maps (4 sets x 2 frames), got $((after - before))"
grep -q "over 2 gray quantizations" "$out/band.txt" || fail "eval band's title: $(head -n 2 "$out/band.txt")"
for name in urban_13 urban_14 wet_road_9 highway_31; do
  dec=$(awk -v n="$name" '$1 == n {print $4}' "$out/first.txt")
  row=$(grep -m1 "^$name " "$out/band.txt") || fail "no band row for $name: $(cat "$out/band.txt")"
  [[ $(awk '{print $2}' <<<"$row") == "$dec" ]] || fail "$name's decoder column differs from eval synthetic's $dec: $row"
  [[ -s "$out/sets/$name.gray0.5.txt" ]] || fail "no table for $name at offset 0.5"
  # min <= decoder F1 <= max
  awk -v d="${dec##*/}" '{split($3, f, "/"); exit !(f[1] <= d + 1e-9 && d <= f[3] + 1e-9)}' <<<"$row" \
    || fail "$name's decoder F1 lies outside its band: $row"
done
want=$("$BIN/bench_detection" --data "$out/sets/urban_14_2" --max-distance 40 --visible --cache "$out/sets/disparity_cache" \
  --gray-offset 0.5 2>&1 | awk '/^stixel \+ SNV/ {print $NF}')
got=$(awk '/^stixel \+ SNV/ {print $NF}' "$out/sets/urban_14.gray0.5.txt")
[[ -n "$want" && "$want" == "$got" ]] || fail "urban_14 at offset 0.5: bench_detection says F1 $want, eval band's table $got"
pass "eval band scores each set on the decoder's gray and on the requantized one"

# --compare: a paired row per set, each cell "TP/FP->TP/FP" at one quantization; the
# "with" side is what bench_detection gives with that key.
grep -q "^paired, stixel + SNV TP/FP without -> with stixel.max_height_above_ground_m=1.5, per quantization" "$out/band.txt" \
  || fail "no paired table: $(cat "$out/band.txt")"
row=$(grep "^urban_14 .*->" "$out/band.txt") || fail "no paired row for urban_14: $(cat "$out/band.txt")"
[[ $(grep -cE '^[a-z_0-9]+ +[0-9]+/[0-9]+->[0-9]+/[0-9]+ +[0-9]+/[0-9]+->[0-9]+/[0-9]+ +[-+][0-9.]+ +[0-9]+/[0-9]+$' "$out/band.txt") == 4 ]] \
  || fail "expected 4 paired rows: $(cat "$out/band.txt")"
with=$("$BIN/bench_detection" --data "$out/sets/urban_14_2" --max-distance 40 --visible --cache "$out/sets/disparity_cache" \
  --gray-offset 0.5 --set stixel.max_height_above_ground_m=1.5 2>&1 | awk '/^stixel \+ SNV/ {print $(NF-5) "/" $(NF-4)}')
without=$(awk '/^stixel \+ SNV/ {print $(NF-5) "/" $(NF-4)}' "$out/sets/urban_14.gray0.5.txt")
[[ $(awk '{print $3}' <<<"$row") == "$without->$with" ]] || fail "urban_14's paired cell at 0.5 should be $without->$with: $row"
pass "eval band --compare pairs each quantization ($without->$with)"

expect_error band "'1.5'" --offsets "0.25 1.5"
expect_error band "'--frobnicate'" --frobnicate
expect_error synthetic "true-disparity uses none" --gray-offset 0.5 --true-disparity
expect_error synthetic "'2'" --gray-offset 2
rc=0
"$BIN/bench_detection" --data "$out/sets/urban_14_2" --gray-offset nan >"$out/bad.txt" 2>&1 || rc=$?
[[ $rc == 2 ]] && grep -q "gray-offset wants a number in \[0, 1), got 'nan'" "$out/bad.txt" \
  || fail "bench_detection --gray-offset nan: exit $rc, $(head -n 1 "$out/bad.txt")"
pass "bad offsets end with a line naming them and exit 2"
