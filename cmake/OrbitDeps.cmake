# Third-party libraries, all from Debian 12 packages (see scripts/setup.sh).
#
# The device library's: OpenCV's modules, Threads, gRPC and Protobuf, found as the installed
# package finds them.
include(${CMAKE_CURRENT_LIST_DIR}/OrbitClientDependencies.cmake)
if(ORBIT_DEVICE_ONLY)
  return()
endif()

# FLANN (the view index's kd-trees) is used header-only; its headers use lz4.
if(NOT TARGET flann::flann)
  find_path(FLANN_INCLUDE_DIR flann/flann.hpp REQUIRED)
  find_path(LZ4_INCLUDE_DIR lz4.h REQUIRED)
  find_library(LZ4_LIBRARY lz4 REQUIRED)
  add_library(flann::flann INTERFACE IMPORTED)
  set_target_properties(flann::flann PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${FLANN_INCLUDE_DIR};${LZ4_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${LZ4_LIBRARY}")
endif()

# hnswlib (header only): the view index's graphs of object summaries, which propose an engine's
# candidate objects (docs/design.md#object-candidates).
if(NOT TARGET hnswlib::hnswlib)
  find_path(HNSWLIB_INCLUDE_DIR hnswlib/hnswlib.h REQUIRED)
  add_library(hnswlib::hnswlib INTERFACE IMPORTED)
  set_target_properties(hnswlib::hnswlib PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${HNSWLIB_INCLUDE_DIR}")
endif()

find_package(PkgConfig REQUIRED)

# prometheus-cpp: the server's metrics (server/server_metrics.h) and their HTTP endpoint
# (`orbit serve --metrics-listen`, server/metrics_endpoint.h: the pull library's Exposer).
find_package(prometheus-cpp CONFIG REQUIRED)

# tcmalloc (gperftools' minimal build): build/orbit's allocator. gRPC, protobuf and the engines
# allocate on every frame, and with glibc's malloc a loaded server spends a noticeable share of
# every frame in it; with tcmalloc it answers more frames per second (docs/results/load.md,
# "The allocator"). Off under sanitizers, which bring their own.
option(ORBIT_TCMALLOC "Link build/orbit with tcmalloc" ON)
if(ORBIT_TCMALLOC AND CMAKE_CXX_FLAGS MATCHES "-fsanitize")
  message(STATUS "ORBIT_TCMALLOC off: a sanitizer build uses the sanitizer's allocator")
  set(ORBIT_TCMALLOC OFF)
endif()
if(ORBIT_TCMALLOC)
  pkg_check_modules(TCMALLOC REQUIRED IMPORTED_TARGET libtcmalloc_minimal)
endif()
