# The third-party libraries of the device library (orbit_client and the core/ layers, orbit_api and
# orbit_proto it links), as imported targets. Used by the build (cmake/OrbitDeps.cmake) and by
# the installed package (OrbitClientConfig.cmake), so that both find them the same way.
#
# Debian splits OpenCV into per-module -dev packages that ship no CMake config, so the modules
# are found by hand: core, imgproc, imgcodecs; video and videoio (captures:
# client/capture_reader.h) and opencv_contrib's tracking (client/object_tracker.h,
# libopencv-contrib-dev).

find_path(OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
foreach(module core imgproc imgcodecs video videoio tracking)
  if(NOT TARGET opencv::${module})
    find_library(OPENCV_${module}_LIBRARY opencv_${module} REQUIRED)
    add_library(opencv::${module} UNKNOWN IMPORTED)
    set_target_properties(opencv::${module} PROPERTIES
      IMPORTED_LOCATION "${OPENCV_${module}_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${OPENCV_INCLUDE_DIR}")
  endif()
endforeach()

# Abseil's thread-safety annotations (core/base/mutex.h) are a header of libabsl-dev, which
# Debian's libgrpc++-dev depends on, in the default include path: nothing to find or link.

find_package(Threads REQUIRED)
# gRPC and Protobuf (Debian ships gRPC's CMake config; Protobuf is found by CMake's module).
find_package(Protobuf REQUIRED)
if(CMAKE_CROSSCOMPILING)
  # gRPC's CMake config also imports its protoc plugins, programs of the target, and refuses to
  # load from a sysroot that lacks them; a cross build needs only the libraries (the build
  # machine's protoc and plugin generate the code: proto/CMakeLists.txt), found by pkg-config.
  if(NOT TARGET gRPC::grpc++)
    find_package(PkgConfig REQUIRED)
    pkg_check_modules(ORBIT_GRPCXX REQUIRED IMPORTED_TARGET grpc++)
    add_library(gRPC::grpc++ INTERFACE IMPORTED)
    set_target_properties(gRPC::grpc++ PROPERTIES INTERFACE_LINK_LIBRARIES PkgConfig::ORBIT_GRPCXX)
  endif()
else()
  find_package(gRPC CONFIG REQUIRED)
endif()
