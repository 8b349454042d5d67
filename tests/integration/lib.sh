# Shared by the multiprocess tests: a private LCM bus and child bookkeeping.
# Each test re-executes itself inside a fresh network namespace whose loopback
# carries multicast, so no traffic leaves the namespace and tests cannot hear
# each other or anything else on the machine.
set -euo pipefail

: "${NERV_BUILD:?set by ctest}"
: "${NERV_ROOT:?set by ctest}"
BIN="$NERV_BUILD/bin"
URL="udpm://239.255.76.67:7667?ttl=0&recv_buf_size=4194304"
SERVICES=(stereo_matcher stixel snv_extrinsic validator)
# An lcm-logger on this bus, for pgrep -f (an extended regex: the URL's '?' and '.' escaped).
LOGGER_PATTERN="lcm-logger --lcm-url=$(printf '%s' "$URL" | sed 's/[][\.*^$?+(){}|]/\\&/g')"

fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok: $*"; }
# PIDs of the programs whose command line starts with $1 (a path, e.g. "$BIN/stixel "). A cross
# build's tests (tools/nerv cross --test) run them through binfmt_misc, which puts the
# emulator in front: /usr/bin/qemu-aarch64-static $BIN/stixel ...
pgrep_program() { pgrep -f "^(/usr/bin/qemu-aarch64-static )?$1"; }
# The same for the build's programs: $BIN/$1 ("stixel " for the stixel stage, "" for any).
nerv_pgrep() { pgrep_program "$BIN/$1"; }

enter_private_bus() {
  if [[ "${NERV_IN_NETNS:-}" == 1 ]]; then return; fi
  if ! unshare -n true 2>/dev/null; then echo "SKIP: cannot create a network namespace" >&2; exit 77; fi
  exec env NERV_IN_NETNS=1 unshare -n -- bash -c \
    'ip link set lo up && ip link set lo multicast on && ip route add 224.0.0.0/4 dev lo && exec bash "$@"' \
    bash "$0" "$@"
}

CHILDREN=()
start_child() {  # start_child LOGFILE CMD...
  local log="$1"; shift
  "$@" >"$log" 2>&1 &
  CHILDREN+=($!)
}
stop_children() {
  local pid
  for pid in "${CHILDREN[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  for pid in "${CHILDREN[@]}"; do
    for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -KILL "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
  done
  CHILDREN=()
}

# wait_until TIMEOUT_S CMD...: bounded retry, never a bare sleep.
wait_until() {
  local limit=$(( $1 * 20 )); shift
  for _ in $(seq 1 "$limit"); do
    if "$@"; then return 0; fi
    sleep 0.05
  done
  return 1
}

# A short rendered sequence (cached in the build tree).
synthetic_sequence() {  # synthetic_sequence SCENE FRAMES -> prints the folder
  local dir="$NERV_BUILD/test_data/$1_$2" stamp
  # Re-rendered whenever the generator or the scene changes.
  stamp=$(cat "$BIN/nerv_synth" "$NERV_ROOT/config/scenes/$1.yaml" | md5sum | cut -d' ' -f1)
  if [[ "$(cat "$dir/.complete" 2>/dev/null)" != "$stamp" ]]; then
    rm -rf "$dir"
    "$BIN/nerv_synth" --scene "$1" --frames "$2" --out "$dir" --quiet >/dev/null 2>&1 || fail "nerv_synth $1 failed"
    echo "$stamp" >"$dir/.complete"
  fi
  echo "$dir"
}

kitti_or_synthetic() {  # the KITTI 0926 frames, or the synthetic urban sequence when ../shared/data is absent
  local d="$NERV_ROOT/../shared/data/kitti_raw_0926_seq"
  if [[ -d "$d" ]]; then echo "$d"; else synthetic_sequence urban 11; fi
}

matcher_field() {  # matcher_field NAME KEY: errors, frames_in, frames_out or a gauge of the stereo_matcher in $tmp/NAME/summary.json
  tr -d '\n ' <"$tmp/$1/summary.json" | grep -o '"stereo_matcher/0":{[^}]*}' | grep -o "\"$2\":[^,}]*" | cut -d: -f2
}

run_pipeline() {  # run_pipeline NAME DATA [ARGS...]: tools/nerv run of DATA into $tmp/NAME, its output in $tmp/NAME.txt
  local name="$1" data="$2"
  shift 2
  "$NERV_ROOT/tools/nerv" run --data "$data" --out "$tmp/$name" "$@" >"$tmp/$name.txt" 2>&1 \
    || fail "$name: nerv run exited with $?: $(tail -n 3 "$tmp/$name.txt")"
}

# An installed nerv (a prefix, an unpacked package) runs on its own: its nerv_up with its
# config, its nerv_source sending 6 urban frames; fails unless every one is detected.
# Sets INSTALLED_RUN to the source's last words ("sent 6 frames in ... s, 6 with DETECTIONS");
# not called in $(...), so a failure ends the test and its children are stopped.
# run_installed_pipeline BINDIR CONFIG WORKDIR: nerv_up and its services from BINDIR on 6 frames
# of the urban scene; every frame must be detected. INSTALLED_AS (an array, may be empty): a
# command nerv_up runs under, e.g. setpriv to run it as another user.
INSTALLED_AS=()
run_installed_pipeline() {
  local bin=$1 config=$2 work=$3 data
  data=$(synthetic_sequence urban 6)
  start_child "$work/up.log" "${INSTALLED_AS[@]}" "$bin/nerv_up" --config "$config" --lcm-url "$URL" --quiet
  "$bin/nerv_source" --data "$data" --rate 5 --lcm-url "$URL" --drain-timeout 20 \
    --wait-for stereo_matcher,stixel,snv_extrinsic,validator 2>"$work/source.log" \
    || fail "the pipeline of $bin did not detect every frame: $(tail -c 300 "$work/source.log"; cat "$work/up.log")"
  # who ran them: nerv_up and its four services (INSTALLED_USERS, e.g. "5 nobody")
  INSTALLED_USERS=$(pgrep_program "$bin/" | xargs -r ps -o user= -p | sort | uniq -c | sed 's/^ *//')
  stop_children
  INSTALLED_RUN=$(tail -n1 "$work/source.log" | grep -o 'sent [0-9]* frames.*')
}

no_survivors() {  # no process of this build left running
  ! nerv_pgrep "" >/dev/null && ! pgrep -f "$LOGGER_PATTERN" >/dev/null
}

# best_kept_iou FILE X1 Y1 X2 Y2: the best IoU of a kept detection in FILE (DETECTIONS as
# nerv_export --json writes them) with the box X1,Y1-X2,Y2; printed with two decimals.
best_kept_iou() {
  grep -o '{"roi_id":[^}]*}' "$1" | grep '"kept":true' | awk -F'[:,]' -v lx1="$2" -v ly1="$3" -v lx2="$4" -v ly2="$5" '
    { for (i = 1; i < NF; i++) v[$i] = $(i + 1);
      x1 = v["\"x\""]; y1 = v["\"y\""]; x2 = x1 + v["\"w\""]; y2 = y1 + v["\"h\""];
      ix = (x2 < lx2 ? x2 : lx2) - (x1 > lx1 ? x1 : lx1); iy = (y2 < ly2 ? y2 : ly2) - (y1 > ly1 ? y1 : ly1);
      inter = (ix > 0 && iy > 0) ? ix * iy : 0;
      iou = inter / ((x2 - x1) * (y2 - y1) + (lx2 - lx1) * (ly2 - ly1) - inter);
      if (iou > best) best = iou }
    END { printf "%.2f", best }'
}

# stage_down_and_back STAGE WAIT_FLAG DIR: the pipeline without STAGE on 40 frames of the
# urban scene at 10 Hz (the source with WAIT_FLAG: --drain-timeout 20 when DETECTIONS must
# come, --no-wait when they cannot), then STAGE started by hand and 10 more frames (the
# source counting from 0 again) that must all come out as DETECTIONS. Everything on the bus
# is logged to DIR/run.lcmlog; STAGE_BACK_US is the time [us] at which STAGE came back.
# (Not in a subshell: the children stay in CHILDREN for the caller's trap.)
stage_down_and_back() {
  local stage=$1 wait_flag=$2 dir=$3 data others
  data=$(synthetic_sequence urban 20)
  others=$(IFS=,; for s in "${SERVICES[@]}"; do [[ $s == "$stage" ]] || echo -n "$s,"; done)
  others=${others%,}
  start_child "$dir/logger.log" lcm-logger --lcm-url="$URL" -f -q "$dir/run.lcmlog"
  start_child "$dir/up.log" "$BIN/nerv_up" --config "$NERV_ROOT/config/pipeline.yaml" --lcm-url "$URL" \
    --services "$others" --quiet
  "$BIN/nerv_source" --data "$data" --repeat 2 --rate 10 --lcm-url "$URL" $wait_flag \
    --wait-for "$others" 2>"$dir/source1.log" || fail "without $stage: $(tail -c 300 "$dir/source1.log")"
  sleep 1
  STAGE_BACK_US=$(( $(date +%s%N) / 1000 ))
  start_child "$dir/$stage.log" "$BIN/$stage" --lcm-url "$URL"
  "$BIN/nerv_source" --data "$data" --rate 10 --frames 10 --lcm-url "$URL" --drain-timeout 20 \
    --wait-for "$(IFS=,; echo "${SERVICES[*]}")" 2>"$dir/source2.log" \
    || fail "with $stage back not every frame came out: $(tail -c 300 "$dir/source2.log")"
  sleep 0.3
  stop_children
}
