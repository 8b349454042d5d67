#!/usr/bin/env bash
# An arm64 (aarch64) sysroot of nerv's dependencies, from Debian's own arm64 packages, for
# building nerv for a Jetson-class vehicle computer on an x86 one and running its tests
# under qemu-user (tools/nerv cross calls it):
#
#   tools/cross/arm64_sysroot.sh DIR
#
# Debian 12 cannot co-install the arm64 -dev packages of OpenCV next to the amd64 ones
# (apt would remove libopencv-dev), so nothing is installed: the packages are downloaded
# with `apt-get download` and unpacked into DIR with `dpkg -x`. Needs the arm64 architecture
# in dpkg (added here, which only makes apt fetch arm64 indexes too) and network access to
# the Debian mirror. What is fetched: the run-time closure (Depends, Pre-Depends) of the
# libraries nerv links, plus their -dev packages without their dependencies, plus every
# OpenCV library file (OpenCVConfig.cmake checks that each module's library exists).
set -euo pipefail
dir=${1:?usage: arm64_sysroot.sh DIR}
die() { echo "nerv cross: $*" >&2; exit 2; }
for tool in apt-get apt-cache dpkg; do command -v "$tool" >/dev/null || die "$tool is missing"; done
if ! dpkg --print-foreign-architectures | grep -qx arm64; then
  [[ $(id -u) == 0 ]] || die "dpkg lacks the arm64 architecture; as root: dpkg --add-architecture arm64 && apt-get update"
  dpkg --add-architecture arm64
  apt-get update -qq
fi
# (an if, not `|| { [[ root ]] && ...; }`, which under set -e would end the script silently)
if ! apt-cache show libc6:arm64 >/dev/null 2>&1 && [[ $(id -u) == 0 ]]; then apt-get update -qq; fi
apt-cache show libc6:arm64 >/dev/null 2>&1 || die "apt has no arm64 index (apt-get update failed?)"

runtime=(libc6 libstdc++6 libgcc-s1 liblcm1 libglib2.0-0 libyaml-cpp0.7
  libopencv-core406 libopencv-imgproc406 libopencv-imgcodecs406 libopencv-calib3d406
  libopencv-ximgproc406 libopencv-video406 libopencv-features2d406 libopencv-flann406)
dev=(libc6-dev liblcm-dev libglib2.0-dev libyaml-cpp-dev libeigen3-dev libgtest-dev libgmock-dev
  libopencv-dev libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev
  libopencv-calib3d-dev libopencv-contrib-dev libopencv-video-dev libopencv-features2d-dev
  libopencv-flann-dev libopencv-dnn-dev libopencv-highgui-dev libopencv-ml-dev
  libopencv-objdetect-dev libopencv-photo-dev libopencv-shape-dev libopencv-stitching-dev
  libopencv-superres-dev libopencv-videoio-dev libopencv-videostab-dev libopencv-viz-dev
  libpcre2-dev libffi-dev libmount-dev libblkid-dev libselinux1-dev libsepol-dev zlib1g-dev)

mkdir -p "$dir/debs"
list="$dir/packages.txt"
{
  apt-cache depends --recurse --no-recommends --no-suggests --no-conflicts --no-breaks \
    --no-replaces --no-enhances "${runtime[@]/%/:arm64}" 2>/dev/null |
    grep -v '^ ' | grep -v '^<' | sed -n 's/:arm64$//p'
  printf '%s\n' "${dev[@]}"
  # every OpenCV 4.6 library (only their files; unused modules' dependencies are not fetched)
  apt-cache pkgnames libopencv- | grep -E '^libopencv-[a-z0-9-]+406$'
} | sort -u > "$list"
echo "nerv cross: $(wc -l < "$list") arm64 packages into $dir" >&2
(
  cd "$dir/debs"
  missing=()
  while read -r p; do
    compgen -G "${p}_*_arm64.deb" >/dev/null || compgen -G "${p}_*_all.deb" >/dev/null || missing+=("$p:arm64")
  done < "$list"
  # apt-get download takes many names at once; a name without an arm64 candidate fails it all,
  # so fall back to one at a time
  if (( ${#missing[@]} )) && ! apt-get download -qq "${missing[@]}" 2>/dev/null; then
    for p in "${missing[@]}"; do apt-get download -qq "$p" 2>/dev/null || apt-get download -qq "${p%:arm64}" 2>/dev/null ||
      echo "nerv cross: no package $p (skipped)" >&2; done
  fi
)
for deb in "$dir"/debs/*.deb; do dpkg -x "$deb" "$dir"; done
# Absolute symlinks (lib*.so -> /lib/aarch64-linux-gnu/...) would point into the host: make
# them relative, so that the folder can be moved.
find "$dir" -path "$dir/debs" -prune -o -type l -lname '/*' -print | while read -r link; do
  target=$(readlink "$link")
  ln -sfn "$(realpath -m --relative-to="$(dirname "$link")" "$dir$target")" "$link"
done
# The BLAS and LAPACK that OpenCV links are chosen by update-alternatives, which dpkg -x does
# not run: take the reference implementations, as a fresh Debian install would without OpenBLAS.
lib="$dir/usr/lib/aarch64-linux-gnu"
for pair in libblas.so.3:blas liblapack.so.3:lapack; do
  name=${pair%%:*} impl=${pair##*:}
  [[ -e "$lib/$name" || ! -e "$lib/$impl/$name" ]] || ln -sfn "$impl/$name" "$lib/$name"
done
# Debian 12 merges /lib into /usr/lib; the loader and the linker look in both.
[[ -e "$dir/lib/aarch64-linux-gnu" ]] || { mkdir -p "$dir/lib"; ln -sfn ../usr/lib/aarch64-linux-gnu "$dir/lib/aarch64-linux-gnu"; }
[[ -e "$dir/lib/ld-linux-aarch64.so.1" ]] || ln -sfn aarch64-linux-gnu/ld-linux-aarch64.so.1 "$dir/lib/ld-linux-aarch64.so.1"
echo "nerv cross: sysroot ready in $dir" >&2
