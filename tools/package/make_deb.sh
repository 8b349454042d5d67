#!/usr/bin/env bash
# A Debian package of a built tree, for vehicle computers that should not each build nerv:
#
#   tools/package/make_deb.sh BUILD_DIR OUT_DIR      (tools/nerv package calls it)
#
# Layout (README "Installing on a vehicle computer"):
#   /opt/nerv/bin/               the services, nerv_up and the tools (nerv_up starts the
#                                services it finds next to itself)
#   /opt/nerv/share/nerv/        configs, camera presets, scenes, message definitions, types jar
#   /usr/bin/nerv_*              links to the nerv_-named programs (the services' own names,
#                                e.g. `validator`, stay off PATH)
#   /etc/nerv/pipeline.yaml      the config the unit reads; a dpkg conffile, so an upgrade
#                                keeps the vehicle's edits (and asks when both changed)
#   /lib/systemd/system/nerv.service, /usr/lib/sysctl.d/60-nerv-lcm.conf
# Depends come from dpkg-shlibdeps on the binaries (for an aarch64 cross build, tools/nerv
# cross --package: from the shlibs files of its sysroot's arm64 packages), plus liblcm-bin
# (lcm-logger, for run.record). The binaries are compiled for the build's -march (NERV_MARCH, `native` by
# default): preinst refuses a computer whose CPU lacks an instruction set the build uses,
# with a line naming it, instead of services that die of SIGILL in a restart loop.
set -euo pipefail

build=$(cd "${1:?usage: make_deb.sh BUILD_DIR OUT_DIR}" && pwd)
out=${2:?usage: make_deb.sh BUILD_DIR OUT_DIR}
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
die() { echo "nerv package: $*" >&2; exit 2; }
for tool in dpkg-deb dpkg-shlibdeps cmake; do
  command -v "$tool" >/dev/null || die "$tool is missing (Debian packages dpkg-dev, cmake)"
done
[[ -f "$build/CMakeCache.txt" ]] || die "$build is not a configured build folder"
[[ -x "$build/bin/nerv_up" ]] || die "$build/bin/nerv_up is missing: build first"
cache() { sed -n "s/^$1:[A-Z]*=//p" "$build/CMakeCache.txt"; }
# A cross build (tools/nerv cross) has another architecture's binaries, whose Depends
# dpkg-shlibdeps cannot find among this computer's packages: they come from the shlibs files
# of the Debian packages its sysroot was made of (tools/cross/arm64_sysroot.sh keeps them).
sysroot=""
arch=$(dpkg --print-architecture)
cxx=$(cache CMAKE_CXX_COMPILER)
runner=()  # what runs the build's programs here
march_hint="tools/nerv package --march x86-64-v2, -v3 or -v4"  # for preinst's refusal
if [[ -n "$(cache CMAKE_TOOLCHAIN_FILE)" ]]; then
  command -v readelf >/dev/null || die "readelf is missing (Debian package binutils)"
  machine=$(readelf -h "$build/bin/nerv_up" | sed -n 's/^ *Machine: *//p')
  [[ "$machine" == AArch64 ]] ||
    die "$build is a cross build for '$machine'; only aarch64 ones (tools/nerv cross) are packaged"
  cxx=aarch64-linux-gnu-g++
  sysroot=$(cache NERV_SYSROOT)
  compgen -G "$sysroot/debs/*.deb" >/dev/null ||
    die "$build is a cross build whose sysroot '$sysroot' has no debs/ (tools/cross/arm64_sysroot.sh keeps them there): its Depends come from their shlibs files"
  command -v qemu-aarch64-static >/dev/null || die "qemu-aarch64-static is missing (Debian package qemu-user-static): it reads the build's version"
  arch=arm64
  runner=(qemu-aarch64-static -L "$sysroot")
  march_hint="tools/nerv cross --package --march armv8-a, armv8.2-a, ..."
fi

# Version: the project's, then the commit count (so a later commit sorts higher for apt) and
# hash of the build's source, as `nerv_up --version` says it: nerv 0.1.0 (6bc2d5f[-dirty]).
stamp=$("${runner[@]}" "$build/bin/nerv_up" --version) || die "${runner[*]} $build/bin/nerv_up --version failed"
stamp=$(sed -n 's/^nerv_up: nerv \([^ ]*\) (\(.*\))$/\1 \2/p' <<<"$stamp")
[[ -n "$stamp" ]] || die "cannot read the build's version from nerv_up --version"
read -r project describe <<<"$stamp"
hash=${describe%-dirty}
count=$(git -C "$root" rev-list --count "$hash" 2>/dev/null) || die "commit $hash of the build is not in $root"
version="$project+$count.g$hash"
[[ "$describe" == *-dirty ]] && version+=".dirty"

# The instruction sets the compiler may use for this build's -march.
march=""
if [[ "$(cache NERV_NATIVE)" != OFF ]]; then
  march=$(cache NERV_MARCH)
  march=${march:-native}
fi
required=()
if [[ -n "$march" ]]; then
  # the compiler's macro -> the name /proc/cpuinfo gives the feature (x86 "flags", ARM "Features")
  declare -A flag=(
    [__SSE4_1__]=sse4_1 [__SSE4_2__]=sse4_2 [__POPCNT__]=popcnt [__AVX__]=avx [__AVX2__]=avx2 [__FMA__]=fma
    [__F16C__]=f16c [__BMI__]=bmi1 [__BMI2__]=bmi2 [__MOVBE__]=movbe [__LZCNT__]=abm [__SSE4A__]=sse4a
    [__AVX512F__]=avx512f [__AVX512BW__]=avx512bw [__AVX512VL__]=avx512vl [__AVX512DQ__]=avx512dq
    [__AVX512CD__]=avx512cd [__AVX512VBMI__]=avx512vbmi [__AVX512VBMI2__]=avx512_vbmi2
    [__AVX512IFMA__]=avx512ifma [__AVX512VNNI__]=avx512_vnni [__AVX512BITALG__]=avx512_bitalg
    [__AVX512VPOPCNTDQ__]=avx512_vpopcntdq [__AVX512BF16__]=avx512_bf16
    [__ARM_NEON]=asimd [__ARM_FEATURE_CRC32]=crc32 [__ARM_FEATURE_ATOMICS]=atomics
    [__ARM_FEATURE_QRDMX]=asimdrdm [__ARM_FEATURE_DOTPROD]=asimddp [__ARM_FEATURE_FP16_SCALAR_ARITHMETIC]=fphp
    [__ARM_FEATURE_FP16_VECTOR_ARITHMETIC]=asimdhp [__ARM_FEATURE_JCVT]=jscvt [__ARM_FEATURE_COMPLEX]=fcma
    [__ARM_FEATURE_MATMUL_INT8]=i8mm [__ARM_FEATURE_BF16_VECTOR_ARITHMETIC]=bf16 [__ARM_FEATURE_SVE]=sve
    [__ARM_FEATURE_SVE2]=sve2 [__ARM_FEATURE_AES]=aes [__ARM_FEATURE_SHA2]=sha2)
  while read -r _ macro _; do
    [[ -n "${flag[$macro]:-}" ]] && required+=("${flag[$macro]}")
  done < <("$cxx" -march="$march" -dM -E - </dev/null)
  mapfile -t required < <(printf '%s\n' "${required[@]}" | sort)
fi
# Instruction sets the compiler may use that this computer's kernel does not list in
# /proc/cpuinfo although the CPU has them: a paravirtualised guest's kernel may mask CPUID bits
# that user space still sees (a Zen 4 PVM guest lists neither abm nor sse4a, while CPUID has
# both, GCC's -march=native uses both and lzcnt runs). No /proc/cpuinfo can show them on such a
# kernel, so preinst accepts them missing on a CPU of the build computer's vendor that lists
# every other instruction set the build uses (x86 builds made on x86 only).
hidden=()
vendor=""
if [[ -z "$sysroot" && ${#required[@]} -gt 0 && -r /proc/cpuinfo ]] && grep -q '^vendor_id' /proc/cpuinfo; then
  vendor=$(grep -m1 '^vendor_id' /proc/cpuinfo | cut -d: -f2 | tr -d ' \t')
  build_flags=" $(grep -m1 '^flags' /proc/cpuinfo | cut -d: -f2) "
  for f in "${required[@]}"; do
    [[ "$build_flags" == *" $f "* ]] || hidden+=("$f")
  done
fi

stage=$(mktemp -d)
chmod 0755 "$stage"  # the package's ./ entry: mktemp's 0700 would be the installed /
trap 'rm -rf "$stage" "$stage.shlibs" "$stage.install.log"' EXIT
DESTDIR="$stage" cmake --install "$build" --prefix /opt/nerv >"$stage.install.log" 2>&1 \
  || { cat "$stage.install.log" >&2; rm -f "$stage.install.log"; die "cmake --install failed"; }
rm -f "$stage.install.log"
# The system places of the config, unit and sysctl file (systemd and sysctl do not look in /opt).
mkdir -p "$stage/etc" "$stage/lib/systemd/system" "$stage/usr/lib/sysctl.d" "$stage/usr/bin"
mv "$stage/opt/nerv/etc/nerv" "$stage/etc/nerv"
rmdir "$stage/opt/nerv/etc"
rm -r "$stage/opt/nerv/lib/systemd" "$stage/opt/nerv/lib/sysctl.d"
rmdir "$stage/opt/nerv/lib" 2>/dev/null || true
sed -e 's|@NERV_BINDIR@|/opt/nerv/bin|g' -e 's|@NERV_CONFIG@|/etc/nerv/pipeline.yaml|g' \
  -e 's|Installed by `cmake --install`|Installed by the nerv Debian package|' \
  "$root/deploy/nerv.service.in" >"$stage/lib/systemd/system/nerv.service"
cp "$root/deploy/60-nerv-lcm.conf" "$stage/usr/lib/sysctl.d/"
for program in "$stage"/opt/nerv/bin/nerv_*; do
  ln -s "/opt/nerv/bin/$(basename "$program")" "$stage/usr/bin/$(basename "$program")"
done

# Depends: the shared libraries' packages, as dpkg-shlibdeps reads them from the binaries.
mapfile -t elves < <(find "$stage/opt/nerv/bin" -type f -exec sh -c 'head -c 4 "$1" | grep -q ELF' _ {} \; -print)
(( ${#elves[@]} > 0 )) || die "no programs in the install"
if [[ -z "$sysroot" ]]; then
  mkdir -p "$stage/debian"
  printf 'Source: nerv\n\nPackage: nerv\nArchitecture: any\n' >"$stage/debian/control"
  shlibs=$(cd "$stage" && dpkg-shlibdeps -O -e"${elves[@]}" 2>"$stage/shlibdeps.log") \
    || { cat "$stage/shlibdeps.log" >&2; die "dpkg-shlibdeps failed"; }
  rm -r "$stage/debian" "$stage/shlibdeps.log"
  depends=${shlibs#shlibs:Depends=}
else
  # A cross build: each library the programs need (readelf's NEEDED, libNAME.so.VERSION or
  # libNAME-VERSION.so), looked up as "NAME VERSION dependency" in the shlibs control files of
  # the sysroot's packages, which is what dpkg-shlibdeps falls back to where a library has no
  # symbols file. Their versions are the sysroot's: Debian 12's.
  for deb in "$sysroot"/debs/*.deb; do dpkg-deb -I "$deb" shlibs 2>/dev/null || true; done |
    awk 'NF >= 3 && $1 !~ /:$/ && $1 !~ /^#/' >"$stage.shlibs"
  depends=$(readelf -d "${elves[@]}" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | sort -u |
    while read -r so; do
      if [[ "$so" =~ ^(.+)\.so\.(.+)$ || "$so" =~ ^(.+)-([0-9][0-9.]*)\.so$ ]]; then
        dep=$(awk -v n="${BASH_REMATCH[1]}" -v v="${BASH_REMATCH[2]}" \
          '$1 == n && $2 == v { $1 = ""; $2 = ""; sub(/^ +/, ""); print; exit }' "$stage.shlibs")
      else
        dep=""
      fi
      echo "${dep:-MISSING $so}"
    done | sort -u | paste -sd, | sed 's/,/, /g')
  rm -f "$stage.shlibs"
  [[ "$depends" != *MISSING* ]] ||
    die "no package of the sysroot declares these libraries in its shlibs: $(grep -o 'MISSING [^,]*' <<<"$depends" | cut -d' ' -f2 | paste -sd' ')"
fi
[[ -n "$depends" ]] || die "dpkg-shlibdeps found no dependencies"
depends+=", liblcm-bin"

mkdir -p "$stage/DEBIAN"
installed_kb=$(du -sk --exclude=DEBIAN "$stage" | cut -f1)
{
  echo "Package: nerv"
  echo "Version: $version"
  echo "Architecture: $arch"
  echo "Maintainer: nerv developers <nerv@localhost>"
  echo "Installed-Size: $installed_kb"
  echo "Depends: $depends"
  echo "Recommends: liblcm-java, default-jre-headless"
  echo "Section: science"
  echo "Priority: optional"
  echo "Description: stereo-vision obstacle detection as LCM services"
  echo " Four services (stereo_matcher, stixel, snv_extrinsic, validator) under the"
  echo " supervisor nerv_up, started by the systemd unit nerv.service on"
  echo " /etc/nerv/pipeline.yaml; the log tools as /usr/bin/nerv_*."
  echo " Built from nerv $describe with -march=${march:-default}."
  if (( ${#required[@]} > 0 )); then echo " Needs a CPU with: ${required[*]}."; fi
} >"$stage/DEBIAN/control"
echo "/etc/nerv/pipeline.yaml" >"$stage/DEBIAN/conffiles"

# preinst: the CPU check. NERV_CPUINFO lets the test give it another CPU's flags.
cat >"$stage/DEBIAN/preinst" <<EOF
#!/bin/sh
set -e
required="${required[*]}"
hidden="${hidden[*]}"  # required, but not listed by the build computer's kernel either
vendor="$vendor"
cpuinfo="\${NERV_CPUINFO:-/proc/cpuinfo}"
[ -n "\$required" ] || exit 0
[ -r "\$cpuinfo" ] || { echo "nerv: \$cpuinfo is unreadable: cannot check that this CPU runs the build" >&2; exit 0; }
flags=" \$(grep -m1 -E '^(flags|Features)' "\$cpuinfo" | cut -d: -f2) "  # x86, ARM
missing=""
unlisted=""
for f in \$required; do
  case "\$flags" in
    *" \$f "*) ;;
    *) case " \$hidden " in *" \$f "*) unlisted="\$unlisted \$f" ;; *) missing="\$missing \$f" ;; esac ;;
  esac
done
if [ -z "\$missing" ] && [ -n "\$unlisted" ]; then
  this_vendor=\$(grep -m1 '^vendor_id' "\$cpuinfo" | cut -d: -f2 | tr -d ' \t')
  if [ "\$this_vendor" = "\$vendor" ]; then
    echo "nerv: this computer's kernel does not list\$unlisted in \$cpuinfo, nor did the build computer's (\$vendor), whose CPU has them; accepted: it lists every other instruction set the build uses" >&2
  else
    missing="\$unlisted"
  fi
fi
if [ -n "\$missing" ]; then
  echo "nerv: this package was built with -march=$march, and this CPU lacks:\$missing; its services would die of SIGILL. Build nerv on this computer, or package it with a -march this CPU has ($march_hint)" >&2
  exit 1
fi
exit 0
EOF
cat >"$stage/DEBIAN/postinst" <<'EOF'
#!/bin/sh
set -e
if [ "$1" = configure ]; then
  # LCM's 4 MiB receive buffer (full frames are about 1 MB).
  sysctl -q -p /usr/lib/sysctl.d/60-nerv-lcm.conf >/dev/null 2>&1 || echo "nerv: could not apply /usr/lib/sysctl.d/60-nerv-lcm.conf now; it applies at the next boot" >&2
  if [ -d /run/systemd/system ]; then
    systemctl daemon-reload
    # An upgrade restarts a running pipeline on the new build; a first install starts nothing.
    if systemctl is-active --quiet nerv; then systemctl restart nerv; fi
  fi
  if [ -z "$2" ]; then
    echo "nerv: installed. Edit /etc/nerv/pipeline.yaml (lcm_url, run.services), then: systemctl enable --now nerv" >&2
  fi
fi
exit 0
EOF
cat >"$stage/DEBIAN/prerm" <<'EOF'
#!/bin/sh
set -e
if [ "$1" = remove ] && [ -d /run/systemd/system ]; then
  systemctl disable --now nerv >/dev/null 2>&1 || true
fi
exit 0
EOF
cat >"$stage/DEBIAN/postrm" <<'EOF'
#!/bin/sh
set -e
if [ -d /run/systemd/system ]; then systemctl daemon-reload || true; fi
exit 0
EOF
chmod 0755 "$stage/DEBIAN/preinst" "$stage/DEBIAN/postinst" "$stage/DEBIAN/prerm" "$stage/DEBIAN/postrm"
(cd "$stage" && find . -path ./DEBIAN -prune -o -type f -print | sed 's|^\./||' | sort | xargs md5sum) >"$stage/DEBIAN/md5sums"

if (( ${#hidden[@]} > 0 )); then
  echo "nerv package: this computer's kernel does not list ${hidden[*]} in /proc/cpuinfo, which the build may use" \
       "(its CPUID has them): preinst accepts them unlisted on a $vendor CPU that lists every other one" >&2
fi
if [[ "$march" == native ]]; then
  echo "nerv package: built with -march=native: it installs only where the CPU has ${required[*]}" \
       "(preinst checks); for a fleet: tools/nerv package --march x86-64-v3" >&2
fi
mkdir -p "$out"
deb="$out/nerv_${version}_${arch}.deb"
dpkg-deb --root-owner-group -Zxz --build "$stage" "$deb" >/dev/null
echo "$deb"
