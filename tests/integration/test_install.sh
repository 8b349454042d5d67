#!/usr/bin/env bash
# `cmake --install` gives a vehicle computer what it needs: the services, nerv_up and
# the tools in one bin/, the configs and message definitions, a systemd unit that
# starts nerv_up on the installed config and a sysctl file for LCM's receive buffer.
# The installed pipeline runs on its own (nothing from the source or build tree),
# and a second install keeps a config the user edited.
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
tmp=$(mktemp -d)
trap 'stop_children; rm -rf "$tmp"' EXIT
p="$tmp/prefix"
cmake --install "$NERV_BUILD" --prefix "$p" >"$tmp/install.log" 2>&1 || fail "cmake --install: $(tail -3 "$tmp/install.log")"
for f in bin/stereo_matcher bin/stixel bin/snv_extrinsic bin/validator bin/nerv_up bin/nerv_source bin/nerv_export \
         share/nerv/config/pipeline.yaml share/nerv/config/cameras/kitti.yaml share/nerv/lcmtypes/detections_t.lcm \
         etc/nerv/pipeline.yaml lib/systemd/system/nerv.service lib/sysctl.d/60-nerv-lcm.conf; do
  [[ -e "$p/$f" ]] || fail "$f was not installed"
done
unit="$p/lib/systemd/system/nerv.service"
grep -qx "ExecStart=$p/bin/nerv_up --config $p/etc/nerv/pipeline.yaml --quiet" "$unit" \
  || fail "the unit does not start the installed nerv_up on the installed config: $(grep ExecStart "$unit")"
grep -qx "DynamicUser=yes" "$unit" || fail "the unit runs nerv as root: no DynamicUser=yes"
grep -qx "net.core.rmem_max = 4194304" "$p/lib/sysctl.d/60-nerv-lcm.conf" || fail "sysctl file without rmem_max"
if command -v systemd-analyze >/dev/null; then
  out=$(systemd-analyze verify "$unit" 2>&1) || fail "systemd-analyze verify: $out"
  [[ -z "$out" ]] || fail "systemd-analyze verify warns: $out"
  verified=", systemd-analyze verify clean"
fi
pass "installed: $(ls "$p/bin" | wc -l) programs, configs, message definitions, unit and sysctl file${verified:-}"

echo "# edited on this vehicle" >>"$p/etc/nerv/pipeline.yaml"
cmake --install "$NERV_BUILD" --prefix "$p" >"$tmp/install2.log" 2>&1 || fail "second install"
grep -q "edited on this vehicle" "$p/etc/nerv/pipeline.yaml" || fail "a second install replaced the user's config"
pass "a second install keeps the edited etc/nerv/pipeline.yaml"

# What the unit runs, from the prefix alone (a copy of the prefix elsewhere runs too:
# nerv_up finds the services next to itself).
mv "$p" "$tmp/moved"
p="$tmp/moved"
run_installed_pipeline "$p/bin" "$p/etc/nerv/pipeline.yaml" "$tmp"
pass "the installed nerv_up and services, moved elsewhere: $INSTALLED_RUN"
no_survivors || fail "processes survived"
pgrep_program "$p/bin/" >/dev/null && fail "installed processes survived"

# The unit runs it as an unprivileged user of its own (DynamicUser): the pipeline needs no
# privilege. Here as nobody, which owns nothing and may write nowhere in the prefix.
if [[ $EUID -eq 0 ]] && command -v setpriv >/dev/null; then
  chmod 755 "$tmp"
  INSTALLED_AS=(setpriv --reuid=nobody --regid=nogroup --clear-groups --no-new-privs)
  run_installed_pipeline "$p/bin" "$p/etc/nerv/pipeline.yaml" "$tmp"
  INSTALLED_AS=()
  [[ "$INSTALLED_USERS" == "5 nobody" ]] || fail "nerv_up and its services should run as nobody: $INSTALLED_USERS"
  pass "as nobody, with nothing writable (the unit's DynamicUser=yes): $INSTALLED_RUN"
else
  pass "the unit has DynamicUser=yes (not root, or no setpriv: the run as nobody was left out)"
fi
no_survivors || fail "processes survived"
echo "4 passed, 0 failed"
