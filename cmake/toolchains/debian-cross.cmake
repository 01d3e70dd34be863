# The part the cross toolchain files share (aarch64-linux-gnu.cmake, arm-linux-gnueabihf.cmake):
# Debian 12's cross compilers, a sysroot of Debian's packages for the target (scripts/cross.sh
# builds it), and qemu-user to run the target's programs, so that gtest_discover_tests and ctest
# run the tests as on the device. Before including it, a toolchain file sets:
#   ORBIT_CROSS_TRIPLE     the GNU triple and multiarch folder (aarch64-linux-gnu)
#   ORBIT_CROSS_PROCESSOR  CMAKE_SYSTEM_PROCESSOR (aarch64, armv7l)
#   ORBIT_CROSS_ARCH       the Debian architecture (arm64, armhf), which names the sysroot
#   ORBIT_CROSS_QEMU       the qemu-user program (qemu-aarch64, qemu-arm)
#
# The sysroot: -DORBIT_SYSROOT=PATH, else this checkout's build-cross/<arch>/sysroot, where
# scripts/cross.sh puts it.
#
# Programs that run during the build (protoc and grpc_cpp_plugin, proto/CMakeLists.txt) are the
# host's: find_program looks only outside the sysroot. Libraries, headers and packages are the
# target's: found only inside it.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR ${ORBIT_CROSS_PROCESSOR})
set(CMAKE_LIBRARY_ARCHITECTURE ${ORBIT_CROSS_TRIPLE})

set(CMAKE_C_COMPILER ${ORBIT_CROSS_TRIPLE}-gcc)
set(CMAKE_CXX_COMPILER ${ORBIT_CROSS_TRIPLE}-g++)

if(NOT ORBIT_SYSROOT)
  get_filename_component(ORBIT_SYSROOT
    ${CMAKE_CURRENT_LIST_DIR}/../../build-cross/${ORBIT_CROSS_ARCH}/sysroot ABSOLUTE)
endif()
if(NOT EXISTS ${ORBIT_SYSROOT}/usr/include)
  message(FATAL_ERROR "no ${ORBIT_CROSS_ARCH} sysroot at ${ORBIT_SYSROOT}: run "
    "scripts/cross.sh ${ORBIT_CROSS_ARCH}, or give -DORBIT_SYSROOT=PATH")
endif()
# try_compile projects read this file again, without the cache: hand them the sysroot.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES ORBIT_SYSROOT)
set(CMAKE_SYSROOT ${ORBIT_SYSROOT})

# pkg-config (gRPC's package finds RE2 with it) reads the sysroot's .pc files, never the host's,
# and prefixes their paths with the sysroot.
set(ENV{PKG_CONFIG_LIBDIR}
  "${ORBIT_SYSROOT}/usr/lib/${ORBIT_CROSS_TRIPLE}/pkgconfig:${ORBIT_SYSROOT}/usr/share/pkgconfig")
set(ENV{PKG_CONFIG_SYSROOT_DIR} ${ORBIT_SYSROOT})
unset(ENV{PKG_CONFIG_PATH})

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# The target's programs under qemu-user, their dynamic loader and libraries from the sysroot.
find_program(ORBIT_CROSS_QEMU_PROGRAM ${ORBIT_CROSS_QEMU} REQUIRED)
set(CMAKE_CROSSCOMPILING_EMULATOR ${ORBIT_CROSS_QEMU_PROGRAM} -L ${ORBIT_SYSROOT})
