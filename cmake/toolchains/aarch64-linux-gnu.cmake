# Cross-compiling rtmot for 64-bit ARM Linux (Jetson, Raspberry Pi 4/5, Graviton...) from an x86-64
# Debian 12 host, against an arm64 Debian sysroot in a folder (scripts/cross_build.sh builds one).
#
#   cmake -S . -B build-aarch64 -G Ninja \
#     -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/aarch64-linux-gnu.cmake [-DRTMOT_SYSROOT=/path]
#
# Host needs: crossbuild-essential-arm64 (aarch64-linux-gnu-gcc/g++), pkg-config, and qemu-user for
# running the tests (CTest goes through CMAKE_CROSSCOMPILING_EMULATOR).
# Why a sysroot folder and not Debian multiarch (`apt-get install libfoo-dev:arm64`): several arm64 -dev
# packages (OpenCV videoio/imgcodecs, GStreamer plugins-base) conflict with their amd64 twins, so a
# machine cannot hold both the native and the cross build's dependencies.

set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

set(RTMOT_SYSROOT "/opt/rtmot-sysroot-arm64" CACHE PATH "arm64 Debian sysroot (scripts/cross_build.sh makes it)")
# try_compile projects re-read this file without our cache: pass the sysroot on to them.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES RTMOT_SYSROOT)
if(NOT EXISTS "${RTMOT_SYSROOT}/usr/include/aarch64-linux-gnu")
  message(FATAL_ERROR "RTMOT_SYSROOT=${RTMOT_SYSROOT} is not an arm64 Debian sysroot "
                      "(no usr/include/aarch64-linux-gnu): run scripts/cross_build.sh or pass -DRTMOT_SYSROOT=")
endif()

set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_SYSROOT "${RTMOT_SYSROOT}")

# Search the sysroot for libraries, headers and CMake packages; the host only for programs (pkg-config,
# protoc...). The sysroot keeps Debian's multiarch layout: CMake finds usr/lib/aarch64-linux-gnu and
# usr/lib/aarch64-linux-gnu/cmake/<pkg> through CMAKE_LIBRARY_ARCHITECTURE, and usr/share/cmake,
# usr/share/eigen3/cmake through the default prefixes below the root path.
set(CMAKE_FIND_ROOT_PATH "${RTMOT_SYSROOT}")
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# pkg-config (GStreamer): only the sysroot's .pc files, with their paths prefixed by the sysroot.
# FindPkgConfig reads these from the environment at configure time.
set(ENV{PKG_CONFIG_DIR} "")
set(ENV{PKG_CONFIG_LIBDIR}
    "${RTMOT_SYSROOT}/usr/lib/aarch64-linux-gnu/pkgconfig:${RTMOT_SYSROOT}/usr/lib/pkgconfig:${RTMOT_SYSROOT}/usr/share/pkgconfig")
set(ENV{PKG_CONFIG_SYSROOT_DIR} "${RTMOT_SYSROOT}")
unset(ENV{PKG_CONFIG_PATH})

# Run the arm64 test programs (CTest, gtest_discover_tests) through user-mode qemu, with the sysroot's
# dynamic loader and libraries.
find_program(RTMOT_QEMU_AARCH64 qemu-aarch64)
if(RTMOT_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR "${RTMOT_QEMU_AARCH64};-L;${RTMOT_SYSROOT}")
endif()
