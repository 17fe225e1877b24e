# Shared by the aarch64 toolchain files: point CMake, pkg-config and CTest's emulator at an arm64 sysroot.
# Call after CMAKE_SYSROOT is set: rtmot_use_aarch64_sysroot(<sysroot>)

macro(rtmot_use_aarch64_sysroot sysroot)
  # Libraries, headers and CMake packages come from the sysroot; programs (pkg-config, protoc...) from
  # the host. Debian's and Ubuntu's multiarch layout (usr/lib/aarch64-linux-gnu, .../cmake/<pkg>) is
  # found through CMAKE_LIBRARY_ARCHITECTURE; usr/share/cmake through the default prefixes.
  set(CMAKE_FIND_ROOT_PATH "${sysroot}")
  set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
  set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
  set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
  set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

  # pkg-config (GStreamer): only the sysroot's .pc files, their paths prefixed with the sysroot.
  # FindPkgConfig reads these from the environment at configure time.
  set(ENV{PKG_CONFIG_DIR} "")
  set(ENV{PKG_CONFIG_LIBDIR}
      "${sysroot}/usr/lib/aarch64-linux-gnu/pkgconfig:${sysroot}/usr/lib/pkgconfig:${sysroot}/usr/share/pkgconfig")
  set(ENV{PKG_CONFIG_SYSROOT_DIR} "${sysroot}")
  unset(ENV{PKG_CONFIG_PATH})

  # Run the arm64 test programs (CTest, gtest_discover_tests) through user-mode qemu, with the
  # sysroot's dynamic loader and libraries.
  find_program(RTMOT_QEMU_AARCH64 qemu-aarch64)
  if(RTMOT_QEMU_AARCH64)
    set(CMAKE_CROSSCOMPILING_EMULATOR "${RTMOT_QEMU_AARCH64};-L;${sysroot}")
  endif()
endmacro()
