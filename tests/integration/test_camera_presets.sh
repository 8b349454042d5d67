#!/usr/bin/env bash
# The Cityscapes and ZED camera presets through the four services, on the urban scene
# rendered with each preset's rig (config/scenes/urban_cityscapes.yaml, urban_zed.yaml):
# every frame comes out (Cityscapes' gray STEREO_FRAME is 4.2 MB, its DISPARITY 2.45 MB as delta16),
# and the published camera height and pitch are within 2 cm and 0.1 deg of the rig on
# every frame (the ZED rig's short baseline had the pitch 0.4-1.0 deg off before the
# widened plane gate, docs/snv.md "Short baselines").
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

for preset in cityscapes zed; do
  data=$(synthetic_sequence "urban_$preset" 5)
  "$NERV_ROOT/tools/nerv" run --data "$data" --out "$tmp/$preset" --config "$NERV_ROOT/config/cameras/$preset.yaml" \
    --rate 2 --timeout 30 >"$tmp/$preset.txt" 2>&1 || fail "$preset: nerv run exited with $?: $(tail -3 "$tmp/$preset.txt")"
  no_survivors || fail "processes survived"
  grep -q '"frames_out":5' "$tmp/$preset/summary.json" || fail "$preset: not all 5 frames detected: $(head -c 200 "$tmp/$preset/summary.json")"
  truth_h=$(awk '!/^#/ { print $4; exit }' "$data/extrinsics.txt")
  truth_p=$(awk '!/^#/ { print $2; exit }' "$data/extrinsics.txt")
  paste <(grep -o '"height_m":[-0-9.e+]*' "$tmp/$preset/summary.json" | cut -d: -f2) \
        <(grep -o '"pitch_deg":[-0-9.e+]*' "$tmp/$preset/summary.json" | cut -d: -f2) \
    | awk -v th="$truth_h" -v tp="$truth_p" -v name="$preset" '
      { n++; dh = $1 - th; dp = $2 - tp; if (dh < 0) dh = -dh; if (dp < 0) dp = -dp
        if (dh > mh) mh = dh; if (dp > mp) mp = dp }
      END { printf "%s: %d frames, height within %.4f m of %s, pitch within %.3f deg of %s\n", name, n, mh, th, mp, tp
            exit !(n == 5 && mh <= 0.02 && mp <= 0.1) }' || fail "$preset: published pose"
  pass "$preset preset: 5 frames through the services, pose within 2 cm and 0.1 deg"
done
echo "2 passed, 0 failed"
