# Cross-compiling rtmot for an NVIDIA Jetson (JetPack 5/6: Ubuntu 20.04/22.04, aarch64) against a
# sysroot copied from the board. Not testable on the x86 CI; see docs/cross-and-deploy.md.
#
# 1. On the board, install the build dependencies once:
#      sudo apt-get install libopencv-dev libeigen3-dev libgstreamer1.0-dev \
#        libgstreamer-plugins-base1.0-dev libspdlog-dev libcli11-dev libyaml-cpp-dev nlohmann-json3-dev
#    (JetPack's OpenCV is nvidia-opencv-dev / libopencv-dev from the L4T repository; either works.)
# 2. Copy its root to the host, then make its absolute symlinks relative so they point into the copy:
#      rsync -aHzR --delete --info=progress2 jetson:/usr jetson:/lib jetson:/etc/alternatives \
#        jetson:/opt/nvidia "$HOME/jetson-sysroot/"   # /opt/nvidia only if you link VPI/TensorRT
#      scripts/cross_fix_sysroot_links.sh "$HOME/jetson-sysroot"
# 3. Configure with a host cross compiler no newer in glibc/libstdc++ than the board's (Ubuntu 22.04's
#    g++-11-aarch64-linux-gnu for JetPack 6, 20.04's g++-9 for JetPack 5, -DJETSON_CXX=...):
#      cmake -S . -B build-jetson -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/jetson.cmake \
#        -DJETSON_SYSROOT=$HOME/jetson-sysroot -DRTMOT_BUILD_TESTS=OFF -DRTMOT_BUILD_BENCH=OFF
#
# Compile for the board's cores (Orin: Cortex-A78AE = armv8.2-a; Xavier: Carmel = armv8.2-a) so the
# compiler may use the dot-product and FP16 instructions the detector's kernels benefit from.

set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

set(JETSON_SYSROOT "$ENV{HOME}/jetson-sysroot" CACHE PATH "Root file system copied from the Jetson (rsync)")
set(JETSON_CXX "aarch64-linux-gnu-g++" CACHE STRING "Cross C++ compiler matching the board's g++ major version")
set(JETSON_CC "aarch64-linux-gnu-gcc" CACHE STRING "Cross C compiler matching JETSON_CXX")
set(JETSON_ARCH_FLAGS "-march=armv8.2-a" CACHE STRING "Target CPU flags (armv8.2-a covers Xavier and Orin)")
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES JETSON_SYSROOT JETSON_CXX JETSON_CC JETSON_ARCH_FLAGS)
if(NOT EXISTS "${JETSON_SYSROOT}/usr/include/aarch64-linux-gnu")
  message(FATAL_ERROR "JETSON_SYSROOT=${JETSON_SYSROOT} does not look like a copy of a Jetson's /usr "
                      "(no usr/include/aarch64-linux-gnu); see the comment at the top of ${CMAKE_CURRENT_LIST_FILE}")
endif()

set(CMAKE_C_COMPILER "${JETSON_CC}")
set(CMAKE_CXX_COMPILER "${JETSON_CXX}")
set(CMAKE_SYSROOT "${JETSON_SYSROOT}")
set(CMAKE_C_FLAGS_INIT "${JETSON_ARCH_FLAGS}")
set(CMAKE_CXX_FLAGS_INIT "${JETSON_ARCH_FLAGS}")
# L4T keeps the NVIDIA driver libraries (libnvargus, libnvbufsurface...) that GStreamer's nvarguscamerasrc
# and OpenCV's CUDA build pull in outside the multiarch dir: let the linker resolve them.
set(CMAKE_EXE_LINKER_FLAGS_INIT
    "-Wl,-rpath-link,${JETSON_SYSROOT}/usr/lib/aarch64-linux-gnu/tegra -Wl,-rpath-link,${JETSON_SYSROOT}/usr/lib/aarch64-linux-gnu")

# Tests are meant to run on the board itself (ctest there); qemu works too if the host has it.
include("${CMAKE_CURRENT_LIST_DIR}/aarch64-sysroot.cmake")
rtmot_use_aarch64_sysroot("${JETSON_SYSROOT}")
