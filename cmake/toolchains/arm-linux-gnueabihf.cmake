# Cross build for 32-bit ARM with hardware floating point (Debian armhf: ARMv7-A, VFPv3-D16,
# Thumb-2; NEON is not part of the baseline), run under qemu-arm: scripts/cross.sh armhf.
#   cmake -S . -B build-cross/armhf -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/arm-linux-gnueabihf.cmake
set(ORBIT_CROSS_TRIPLE arm-linux-gnueabihf)
set(ORBIT_CROSS_PROCESSOR armv7l)
set(ORBIT_CROSS_ARCH armhf)
set(ORBIT_CROSS_QEMU qemu-arm)
# GCC notes, for every std::span passed by value, that its passing changed in GCC 7.1: only code
# built by an older GCC would disagree, and nothing here links any.
set(CMAKE_CXX_FLAGS_INIT -Wno-psabi)
include(${CMAKE_CURRENT_LIST_DIR}/debian-cross.cmake)
