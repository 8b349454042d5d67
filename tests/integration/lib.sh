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

fail() { echo "FAIL: $*" >&2; exit 1; }
pass() { echo "ok: $*"; }

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

no_survivors() {  # no process of this build left running
  ! pgrep -f "^$BIN/" >/dev/null && ! pgrep -f "lcm-logger --lcm-url=$URL" >/dev/null
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
