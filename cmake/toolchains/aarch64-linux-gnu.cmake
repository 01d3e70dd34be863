# Cross build for 64-bit ARM (Debian arm64), run under qemu-aarch64: scripts/cross.sh arm64.
#   cmake -S . -B build-cross/arm64 -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/aarch64-linux-gnu.cmake
set(ORBIT_CROSS_TRIPLE aarch64-linux-gnu)
set(ORBIT_CROSS_PROCESSOR aarch64)
set(ORBIT_CROSS_ARCH arm64)
set(ORBIT_CROSS_QEMU qemu-aarch64)
include(${CMAKE_CURRENT_LIST_DIR}/debian-cross.cmake)
