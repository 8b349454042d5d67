# Cross build for arm64 (Jetson-class vehicle computers) with Debian's g++-aarch64-linux-gnu
# and a sysroot of Debian's arm64 packages (tools/cross/arm64_sysroot.sh; tools/nerv cross):
#
#   cmake -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake -DNERV_SYSROOT=DIR ..
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
if(NOT NERV_SYSROOT)
  set(NERV_SYSROOT "$ENV{NERV_SYSROOT}")
endif()
if(NOT NERV_SYSROOT OR NOT EXISTS "${NERV_SYSROOT}/usr/include/opencv4")
  message(FATAL_ERROR "NERV_SYSROOT='${NERV_SYSROOT}' is not an arm64 sysroot of nerv's "
                      "dependencies (make one with tools/cross/arm64_sysroot.sh DIR)")
endif()
# -march=native means nothing to a cross compiler: the default is the first 64-bit ARM
# (every Jetson, Raspberry Pi 4/5); tools/nerv cross --march armv8.2-a for Xavier and Orin.
set(NERV_MARCH armv8-a CACHE STRING "-march when NERV_NATIVE is on: armv8-a, armv8.2-a, ...")
# try_compile projects need the sysroot too
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES NERV_SYSROOT)
set(CMAKE_SYSROOT "${NERV_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH "${NERV_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)   # lcm-gen, javac: the host's
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(ENV{PKG_CONFIG_SYSROOT_DIR} "${NERV_SYSROOT}")
set(ENV{PKG_CONFIG_LIBDIR} "${NERV_SYSROOT}/usr/lib/aarch64-linux-gnu/pkgconfig:${NERV_SYSROOT}/usr/share/pkgconfig")
# Tests run under qemu-user with the sysroot as the loader's prefix; the tests that start
# other programs need qemu registered with binfmt_misc and QEMU_LD_PREFIX (tools/nerv cross --test).
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64-static -L "${NERV_SYSROOT}")
