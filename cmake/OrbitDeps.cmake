# Third-party libraries, all from Debian 12 packages (see scripts/setup.sh).
#
# The device library's: OpenCV's modules, FLANN, Threads, gRPC and Protobuf, found as the
# installed package finds them.
include(${CMAKE_CURRENT_LIST_DIR}/OrbitClientDependencies.cmake)

find_package(PkgConfig REQUIRED)

# prometheus-cpp: the server's metrics (server/server_metrics.h) and their HTTP endpoint
# (`orbit serve --metrics-listen`, server/metrics_endpoint.h: the pull library's Exposer).
find_package(prometheus-cpp CONFIG REQUIRED)
