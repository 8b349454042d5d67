#!/usr/bin/env bash
# Operating nerv like vehicle software:
#  - a drive recorded by lcm-logger replays through fresh services with the real
#    lcm-logplayer, and two replays give identical STIXELS, EXTRINSICS,
#    SURFACE_NORMALS and DETECTIONS (timing fields aside), also identical to the live run;
#  - the logger lost no message (published vs logged counts);
#  - a Java client on lcm.jar + nerv_types.jar decodes every event (what lcm-spy relies on).
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
data=$(synthetic_sequence urban 6)
tmp=$(mktemp -d)
trap 'stop_children; rm -rf "$tmp"' EXIT

"$NERV_ROOT/tools/nerv" run --data "$data" --out "$tmp/live" --rate 10 >/dev/null 2>&1 || fail "live run"
"$NERV_ROOT/tools/nerv" replay "$tmp/live/nerv.lcmlog" --out "$tmp/r1" --speed 0.5 2>/dev/null || fail "replay 1"
# The second replay with a config whose channel_prefix is not the log's: the stages take the
# log's (none here), say so, and give the same output.
sed 's/^channel_prefix:.*/channel_prefix: "X_"/' "$NERV_ROOT/config/pipeline.yaml" >"$tmp/x.yaml"
"$NERV_ROOT/tools/nerv" replay "$tmp/live/nerv.lcmlog" --out "$tmp/r2" --speed 0.5 --config "$tmp/x.yaml" 2>"$tmp/r2.txt" \
  || fail "replay 2 (config prefix X_): $(tail -2 "$tmp/r2.txt")"
grep -q "the stages run with ''" "$tmp/r2.txt" || fail "replay 2 did not say the prefix it ran with: $(cat "$tmp/r2.txt")"
no_survivors || fail "processes survived a replay"
ch=STIXELS,EXTRINSICS,SURFACE_NORMALS,DETECTIONS
"$BIN/nerv_diff" "$tmp/r1/nerv.lcmlog" "$tmp/r2/nerv.lcmlog" --channels $ch || fail "two replays differ"
"$BIN/nerv_diff" "$tmp/live/nerv.lcmlog" "$tmp/r1/nerv.lcmlog" --channels $ch || fail "replay differs from the live run"
pass "replays are deterministic and equal the live run (the second with a config of another channel_prefix)"

# A drive recorded under a channel prefix replays under it, with the default config. Two cameras
# on one bus (FRONT_ and REAR_ pipelines side by side): each run's logger records both, its
# summary reads its own; a replay of that log runs stages for each camera.
"$NERV_ROOT/tools/nerv" run --data "$data" --out "$tmp/rear" --prefix REAR_ --rate 10 >"$tmp/rear.txt" 2>&1 &
rear=$!
"$NERV_ROOT/tools/nerv" run --data "$data" --out "$tmp/front" --prefix FRONT_ --rate 10 >"$tmp/front.txt" 2>&1 || fail "FRONT_ live run: $(tail -3 "$tmp/front.txt")"
wait $rear || fail "REAR_ live run: $(tail -3 "$tmp/rear.txt")"
for p in FRONT_ REAR_; do
  s="$tmp/$(echo ${p%_} | tr A-Z a-z)/summary.json"
  grep -q "\"prefix\":\"$p\"" "$s" || fail "the $p run's summary is not of $p: $(head -c 300 "$s")"
  grep -q '"frames_in":6,"frames_out":6,' "$s" || fail "the $p run's summary does not count its 6 frames: $(head -c 300 "$s")"
done
both="$tmp/front/nerv.lcmlog"
# (the REAR_ run started first: its first frames may precede the FRONT_ run's logger)
nr=$("$BIN/nerv_export" "$both" --json --no-blobs | grep -c '"channel":"REAR_STEREO_FRAME"' || true)
[[ "$nr" -ge 1 ]] || fail "the FRONT_ run's log holds no REAR_STEREO_FRAME: the two runs did not overlap"
line=$("$BIN/nerv_export" "$both" --summary - | head -n1)
[[ "$line" == "this log holds 2 pipelines, by channel prefix: "*"'FRONT_'"*"'REAR_'"*"; choose one with --prefix P" ||
   "$line" == "this log holds 2 pipelines, by channel prefix: "*"'REAR_'"*"'FRONT_'"*"; choose one with --prefix P" ]] \
  || fail "the summary of a two-camera log does not say so: $line"
"$NERV_ROOT/tools/nerv" replay "$both" --out "$tmp/r3" --speed 0.5 2>"$tmp/r3.txt" \
  || fail "replay of the two-camera drive: $(tail -2 "$tmp/r3.txt")"
grep -q "the log holds 2 pipelines" "$tmp/r3.txt" || fail "the replay did not say it ran two pipelines: $(cat "$tmp/r3.txt")"
for p in FRONT_ REAR_; do
  want=6; [[ $p == REAR_ ]] && want=$nr
  n=$("$BIN/nerv_export" "$tmp/r3/nerv.lcmlog" --json --no-blobs | grep -c "\"channel\":\"${p}DETECTIONS\"" || true)
  [[ "$n" -eq "$want" ]] || fail "replay of the two-camera drive: $n ${p}DETECTIONS, expected $want"
  grep -q "\"frames_in\":$want,\"frames_out\":$want," "$tmp/r3/summary.$p.json" || fail "replay's $p summary: $(head -c 300 "$tmp/r3/summary.$p.json")"
done
# the other log tools keep the cameras apart: nerv_diff per prefixed channel, nerv_render one camera
"$BIN/nerv_diff" "$both" "$tmp/r3/nerv.lcmlog" --channels DETECTIONS >"$tmp/diff3.txt" || true
grep -q "^FRONT_DETECTIONS  *6 identical  *0 differ" "$tmp/diff3.txt" && grep -q "^REAR_DETECTIONS " "$tmp/diff3.txt" \
  || fail "nerv_diff did not compare the cameras apart: $(cat "$tmp/diff3.txt")"
"$BIN/nerv_render" "$both" --out "$tmp/render_rear" --prefix REAR_ >"$tmp/render.txt" 2>&1 || fail "nerv_render --prefix REAR_: $(cat "$tmp/render.txt")"
grep -q "nerv_render: $nr frames to" "$tmp/render.txt" || fail "nerv_render --prefix REAR_ did not draw its $nr frames: $(cat "$tmp/render.txt")"
grep -q "'REAR_' (read here)" "$tmp/render.txt" || fail "nerv_render did not say which camera it drew: $(cat "$tmp/render.txt")"
no_survivors || fail "processes survived a replay"
pass "a drive of two cameras (FRONT_, REAR_ on one bus) replayed with stages for each ($nr REAR_ frames in the FRONT_ run's log); each run's summary counted its own 6 frames; nerv_diff and nerv_render kept the cameras apart"

# nothing lost by the logger: every frame and every stage output of the live run is in its log
for c in STEREO_FRAME DISPARITY STIXELS SURFACE_NORMALS EXTRINSICS DETECTIONS; do
  n=$(grep -o '"events_per_channel":{[^}]*}' "$tmp/live/summary.json" | grep -o "\"$c\":[0-9]*" | cut -d: -f2)
  [[ "$n" == 6 ]] || fail "log holds $n $c events, expected 6"
done
pass "lcm-logger recorded all 6 frames on every channel"

# at the pipeline's maximum rate, with a live exporter listening on the bus
"$BIN/nerv_export" --live --json --no-blobs --channels '.*DETECTIONS' --count 6 --seconds 60 >"$tmp/live.jsonl" &
exporter=$!
"$NERV_ROOT/tools/nerv" run --data "$data" --out "$tmp/max" --rate 0 --in-flight 2 >/dev/null 2>&1 || fail "run at --rate 0"
wait $exporter || fail "live export"
[[ $(grep -c '"type":"nerv.detections_t"' "$tmp/live.jsonl") -eq 6 ]] || fail "live export saw $(wc -l <"$tmp/live.jsonl") DETECTIONS"
for c in STEREO_FRAME DISPARITY STIXELS SURFACE_NORMALS EXTRINSICS DETECTIONS; do
  n=$(grep -o '"events_per_channel":{[^}]*}' "$tmp/max/summary.json" | grep -o "\"$c\":[0-9]*" | cut -d: -f2)
  [[ "$n" == 6 ]] || fail "at --rate 0 the log holds $n $c events, expected 6"
done
pass "--rate 0: logger recorded every message, live export saw all 6 DETECTIONS"

command -v javac >/dev/null || { echo "SKIP: javac missing"; exit 77; }
[[ -f "$NERV_BUILD/nerv_types.jar" ]] || fail "nerv_types.jar was not built"
cp=/usr/share/java/lcm.jar:$NERV_BUILD/nerv_types.jar
javac -d "$tmp/java" -cp "$cp" "$(dirname "$0")/LogDecode.java" || fail "javac"
java -cp "$cp:$tmp/java" LogDecode "$tmp/live/nerv.lcmlog" "$NERV_BUILD/nerv_types.jar" >"$tmp/java.txt" \
  || { cat "$tmp/java.txt"; fail "the Java client could not decode every event"; }
grep -q "DETECTIONS detections_t 6" "$tmp/java.txt" || fail "Java client: $(cat "$tmp/java.txt")"
pass "Java client decoded every event: $(tr '\n' ';' <"$tmp/java.txt")"
echo "1 passed, 0 failed"
