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

include("${CMAKE_CURRENT_LIST_DIR}/aarch64-sysroot.cmake")
rtmot_use_aarch64_sysroot("${RTMOT_SYSROOT}")
