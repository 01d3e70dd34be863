# Third-party libraries, all from Debian 12 packages (see scripts/setup.sh).
#
# Debian splits OpenCV into per-module -dev packages that ship no CMake config, so the modules
# the project uses are found by hand and exposed as imported targets: core, imgproc, imgcodecs;
# video and videoio (captures: client/capture_reader.h) and opencv_contrib's tracking
# (client/object_tracker.h, libopencv-contrib-dev).

find_path(OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
foreach(module core imgproc imgcodecs video videoio tracking)
  find_library(OPENCV_${module}_LIBRARY opencv_${module} REQUIRED)
  add_library(opencv::${module} UNKNOWN IMPORTED)
  set_target_properties(opencv::${module} PROPERTIES
    IMPORTED_LOCATION "${OPENCV_${module}_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OPENCV_INCLUDE_DIR}")
endforeach()

find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)

# FLANN (the view index's kd-trees) is used header-only; its headers use lz4.
find_path(FLANN_INCLUDE_DIR flann/flann.hpp REQUIRED)
find_path(LZ4_INCLUDE_DIR lz4.h REQUIRED)
find_library(LZ4_LIBRARY lz4 REQUIRED)
add_library(flann::flann INTERFACE IMPORTED)
set_target_properties(flann::flann PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES "${FLANN_INCLUDE_DIR};${LZ4_INCLUDE_DIR}"
  INTERFACE_LINK_LIBRARIES "${LZ4_LIBRARY}")

# gRPC and Protobuf (Debian ships gRPC's CMake config; Protobuf is found by CMake's module).
find_package(Protobuf REQUIRED)
find_package(gRPC CONFIG REQUIRED)

# prometheus-cpp: the server's metrics (server/server_metrics.h) and their HTTP endpoint
# (`orbit serve --metrics-listen`, server/metrics_endpoint.h: the pull library's Exposer).
find_package(prometheus-cpp CONFIG REQUIRED)
