#!/usr/bin/env bash
# tools/package/make_deb.sh makes a Debian package of the build that a vehicle computer
# installs with dpkg: the programs in /opt/nerv/bin with links to the nerv_* tools in
# /usr/bin, the config as a conffile in /etc/nerv, the unit and the sysctl file where
# systemd and sysctl look, Depends from the binaries' libraries. dpkg accepts it on this
# system (--dry-run: nothing is installed here), its preinst refuses a CPU without the
# build's instruction sets with a line naming them, and the pipeline runs from its files.
# On a cross build (tools/nerv cross --test) the same for its arm64 package, but for dpkg.
source "$(dirname "$0")/lib.sh"
enter_private_bus "$@"
tmp=$(mktemp -d)
trap 'stop_children; rm -rf "$tmp"' EXIT
for tool in dpkg-deb dpkg-shlibdeps; do
  command -v "$tool" >/dev/null || { echo "SKIP: $tool is missing (Debian package dpkg-dev)" >&2; exit 77; }
done

# a cross build (tools/nerv cross) is packaged for its architecture, Depends from the shlibs of
# its sysroot's packages; this computer's dpkg cannot install it, and its CPU check reads ARM's
# "Features"
cross=0
grep -q '^CMAKE_TOOLCHAIN_FILE:' "$NERV_BUILD/CMakeCache.txt" && cross=1
arch=$(dpkg --print-architecture)
((cross)) && arch=arm64
deb=$("$NERV_ROOT/tools/package/make_deb.sh" "$NERV_BUILD" "$tmp/out" 2>"$tmp/make.log") || fail "make_deb.sh: $(cat "$tmp/make.log")"
[[ -f "$deb" ]] || fail "no package: $deb"
field() { dpkg-deb -f "$deb" "$1"; }
hash=$("$BIN/nerv_up" --version | sed -n 's/.*(\([0-9a-f]*\).*/\1/p')
[[ "$(field Package)" == nerv && "$(field Architecture)" == "$arch" ]] || fail "control: $(dpkg-deb -f "$deb")"
[[ "$(field Version)" =~ ^0\.1\.0\+[0-9]+\.g$hash(\.dirty)?$ ]] || fail "version $(field Version) does not name the build $hash"
for dep in libc6 liblcm1 libopencv-core 'libyaml-cpp' liblcm-bin libstdc++6; do
  [[ "$(field Depends)" == *"$dep"* ]] || fail "Depends lacks $dep: $(field Depends)"
done
pass "$(basename "$deb"): $(field Depends | tr ',' '\n' | wc -l) dependencies"

dpkg-deb -c "$deb" | awk '{print $1, $6, $7, $8}' | sed 's/ *$//' >"$tmp/contents"
for f in ./opt/nerv/bin/stereo_matcher ./opt/nerv/bin/validator ./opt/nerv/bin/nerv_up ./etc/nerv/pipeline.yaml \
         ./lib/systemd/system/nerv.service ./usr/lib/sysctl.d/60-nerv-lcm.conf ./opt/nerv/share/nerv/lcmtypes/detections_t.lcm \
         ./opt/nerv/share/nerv/config/cameras/kitti.yaml; do
  grep -q " $f\$" "$tmp/contents" || fail "$f is not in the package"
done
grep -q "^lrwxrwxrwx ./usr/bin/nerv_up -> /opt/nerv/bin/nerv_up$" "$tmp/contents" || fail "no /usr/bin/nerv_up link"
grep -q " ./usr/bin/validator" "$tmp/contents" && fail "a service's own name is on PATH"
grep -qx "drwxr-xr-x ./" "$tmp/contents" || fail "the package's root is not 0755: $(head -n 1 "$tmp/contents")"
dpkg-deb -e "$deb" "$tmp/control"
[[ "$(cat "$tmp/control/conffiles")" == /etc/nerv/pipeline.yaml ]] || fail "conffiles: $(cat "$tmp/control/conffiles")"
dpkg-deb -x "$deb" "$tmp/root"
unit="$tmp/root/lib/systemd/system/nerv.service"
grep -qx "ExecStart=/opt/nerv/bin/nerv_up --config /etc/nerv/pipeline.yaml --quiet" "$unit" || fail "unit: $(grep ExecStart "$unit")"
grep -qx "ConditionPathExists=/etc/nerv/pipeline.yaml" "$unit" || fail "unit condition: $(grep Condition "$unit")"
pass "$(grep -c . "$tmp/contents") entries: programs in /opt/nerv/bin, nerv_* linked from /usr/bin, /etc/nerv/pipeline.yaml a conffile, the unit on /opt/nerv/bin/nerv_up"

if ((cross)); then
  # the CPU check on ARM: a Cortex-A53's features (Raspberry Pi 3, the first 64-bit ARM) and
  # a made-up CPU without Advanced SIMD, which every aarch64 build needs
  printf 'processor\t: 0\nFeatures\t: fp asimd evtstrm crc32 cpuid\n' >"$tmp/a53_cpuinfo"
  printf 'processor\t: 0\nFeatures\t: fp evtstrm cpuid\n' >"$tmp/no_simd_cpuinfo"
  needs=$(field Description | sed -n 's/^ *Needs a CPU with: \(.*\)\.$/\1/p')
  [[ " $needs " == *" asimd "* ]] || fail "an aarch64 build that does not need asimd: '$needs'"
  NERV_CPUINFO="$tmp/no_simd_cpuinfo" sh "$tmp/control/preinst" install >"$tmp/preinst_old.log" 2>&1 \
    && fail "preinst accepted a CPU without asimd"
  grep -q "^nerv: this package was built with -march=[^ ]*, and this CPU lacks:.* asimd.*; its services would die of SIGILL" "$tmp/preinst_old.log" \
    || fail "preinst's refusal: $(cat "$tmp/preinst_old.log")"
  if [[ "$needs" == asimd ]]; then
    NERV_CPUINFO="$tmp/a53_cpuinfo" sh "$tmp/control/preinst" install >"$tmp/preinst.log" 2>&1 \
      || fail "preinst refused a Cortex-A53 for an armv8-a build: $(cat "$tmp/preinst.log")"
    a53=", a Cortex-A53 accepted"
  fi
  pass "preinst on ARM: a CPU without asimd refused${a53:-}: $(cut -c1-100 "$tmp/preinst_old.log")..."
  run_installed_pipeline "$tmp/root/opt/nerv/bin" "$tmp/root/etc/nerv/pipeline.yaml" "$tmp"
  pass "the packaged aarch64 nerv_up and services (under qemu): $INSTALLED_RUN"
  no_survivors || fail "processes survived"
  echo "4 passed, 0 failed"
  exit 0
fi

out=$(dpkg --dry-run -i "$deb" 2>&1) || fail "dpkg --dry-run -i: $out"
pass "dpkg --dry-run -i accepts it on this system"

# The CPU check: this computer passes; one with only the flags of an old CPU does not.
sh "$tmp/control/preinst" install >"$tmp/preinst.log" 2>&1 || fail "preinst refused the computer the build was made on: $(cat "$tmp/preinst.log")"
# Instruction sets this computer's kernel does not list although its CPU has them (a
# paravirtualised guest): accepted on a CPU of the same vendor that lists the others, refused on
# another vendor's.
hidden=$(sed -n 's/^hidden="\(.*\)".*/\1/p' "$tmp/control/preinst")
if [[ -n "$hidden" ]]; then
  grep -q "^nerv: this computer's kernel does not list $hidden in /proc/cpuinfo, nor did the build computer's" "$tmp/preinst.log" \
    || fail "preinst did not say which instruction sets it could not check: $(cat "$tmp/preinst.log")"
  sed 's/^vendor_id.*/vendor_id\t: OtherVendor/' /proc/cpuinfo >"$tmp/other_vendor_cpuinfo"
  NERV_CPUINFO="$tmp/other_vendor_cpuinfo" sh "$tmp/control/preinst" install >"$tmp/preinst_vendor.log" 2>&1 \
    && fail "preinst accepted $hidden unlisted on another vendor's CPU"
  grep -q "and this CPU lacks: $hidden;" "$tmp/preinst_vendor.log" || fail "preinst's refusal: $(cat "$tmp/preinst_vendor.log")"
  pass "preinst: $hidden, which this computer's kernel does not list, accepted on this CPU, refused on another vendor's"
fi
printf 'processor\t: 0\nflags\t\t: fpu sse sse2 ssse3 sse4_1 sse4_2 popcnt\n' >"$tmp/old_cpuinfo"
needs=$(field Description | sed -n 's/^ *Needs a CPU with: \(.*\)\.$/\1/p')
if [[ -n "$needs" && "$needs" != "sse4_1 sse4_2 popcnt" ]]; then
  NERV_CPUINFO="$tmp/old_cpuinfo" sh "$tmp/control/preinst" install >"$tmp/preinst_old.log" 2>&1 \
    && fail "preinst accepted a CPU without $needs"
  grep -q "^nerv: this package was built with -march=[^ ]*, and this CPU lacks:.* avx2.*; its services would die of SIGILL" "$tmp/preinst_old.log" \
    || fail "preinst's refusal: $(cat "$tmp/preinst_old.log")"
  pass "preinst: this CPU accepted, an SSE4.2-only CPU refused: $(cut -c1-120 "$tmp/preinst_old.log")..."
else
  pass "preinst: the build needs no instruction set beyond SSE4.2 (-march $(field Description | grep -o 'march=[^ .]*'))"
fi

# The pipeline from the package's files alone (nerv_up finds the services next to itself).
run_installed_pipeline "$tmp/root/opt/nerv/bin" "$tmp/root/etc/nerv/pipeline.yaml" "$tmp"
pass "the packaged nerv_up and services: $INSTALLED_RUN"
no_survivors || fail "processes survived"
echo "$((${hidden:+1} + 5)) passed, 0 failed"
