# `cmake --install build --prefix P` installs the device library as a C++ package:
#   P/lib/liborbit_client.a and the libraries it links: orbit_api, orbit_proto and the core/
#   layers below them (orbit_model, orbit_descriptor, orbit_base); no view index, engine or
#   decision rule (docs/design.md#layers; tests/install/build_example.cmake checks that the
#   prefix holds these libraries and no others),
#   P/include/: the public API only, that is the headers of client/ and every header of this tree
#   they include, directly or through others (so "client/enroller.h" and "core/descriptor/
#   descriptor.h", never a server's or an engine's internals), at the paths they are included by;
#   P/include/orbit/v1/*.pb.h, the generated API,
#   P/lib/cmake/OrbitClient/: find_package(OrbitClient) gives the target Orbit::orbit_client,
#   P/lib/pkgconfig/orbit-client.pc: pkg-config --cflags --libs orbit-client.
# The third-party libraries are Debian's, found again by the package
# (cmake/OrbitClientDependencies.cmake). examples/capture_client builds against it
# (tests/install/build_example.cmake).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(orbit_client_libraries orbit_client orbit_api orbit_model orbit_descriptor orbit_base
  orbit_proto)
# Inside the build the libraries include from the source and build trees; installed, from
# P/include.
foreach(library IN LISTS orbit_client_libraries)
  if(library STREQUAL orbit_proto)
    continue()
  endif()
  set_target_properties(${library} PROPERTIES INTERFACE_INCLUDE_DIRECTORIES
    "$<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>;$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>")
endforeach()
set_target_properties(orbit_proto PROPERTIES
  INTERFACE_INCLUDE_DIRECTORIES
    "$<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/proto>;$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>"
  INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "$<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/proto>")

# The headers use C++20.
set_property(TARGET orbit_client APPEND PROPERTY INTERFACE_COMPILE_FEATURES cxx_std_20)

install(TARGETS ${orbit_client_libraries} EXPORT OrbitClientTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
# The headers of this tree that the given headers include, directly or through others, and
# the given ones.
function(orbit_header_closure out)
  set(closure "")
  set(queue ${ARGN})
  while(queue)
    list(POP_FRONT queue header)
    if(header IN_LIST closure)
      continue()
    endif()
    list(APPEND closure ${header})
    file(STRINGS ${PROJECT_SOURCE_DIR}/${header} includes REGEX "^#include \"[^\"]+\\.h\"")
    foreach(include IN LISTS includes)
      string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" included "${include}")
      if(EXISTS ${PROJECT_SOURCE_DIR}/${included})
        list(APPEND queue ${included})
      endif()
    endforeach()
  endwhile()
  set(${out} ${closure} PARENT_SCOPE)
endfunction()

file(GLOB client_headers RELATIVE ${PROJECT_SOURCE_DIR} CONFIGURE_DEPENDS
  ${PROJECT_SOURCE_DIR}/client/*.h)
orbit_header_closure(public_headers ${client_headers})
foreach(header IN LISTS public_headers)
  get_filename_component(folder ${header} DIRECTORY)
  install(FILES ${PROJECT_SOURCE_DIR}/${header} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${folder})
endforeach()
install(DIRECTORY ${PROJECT_BINARY_DIR}/proto/orbit/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/orbit
  FILES_MATCHING PATTERN "*.pb.h")

set(orbit_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/OrbitClient)
install(EXPORT OrbitClientTargets NAMESPACE Orbit:: DESTINATION ${orbit_cmake_dir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/OrbitClientConfig.cmake.in
  ${PROJECT_BINARY_DIR}/OrbitClientConfig.cmake INSTALL_DESTINATION ${orbit_cmake_dir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/OrbitClientConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/OrbitClientConfig.cmake
  ${PROJECT_BINARY_DIR}/OrbitClientConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/OrbitClientDependencies.cmake
  DESTINATION ${orbit_cmake_dir})

configure_file(${PROJECT_SOURCE_DIR}/cmake/orbit-client.pc.in
  ${PROJECT_BINARY_DIR}/orbit-client.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/orbit-client.pc
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
