# The installed device library, as an application outside Orbit's tree uses it:
# installs the build into a fresh prefix under /tmp, builds examples/capture_client there with
# find_package(OrbitClient) and again with the compiler and `pkg-config --cflags --libs
# orbit-client` alone, and runs both builds (no arguments: usage, exit 2).
#   cmake -DORBIT_BUILD_DIR=build -DORBIT_SOURCE_DIR=. -DCXX=c++ [-DFLAGS=...] -P build_example.cmake
# FLAGS: the build's own compiler flags (a sanitizer build's -fsanitize=...), used for the
# example too, since the installed static libraries need them at link time.
string(RANDOM LENGTH 10 suffix)
set(work /tmp/orbit-install-test-${suffix})
file(REMOVE_RECURSE ${work})

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    file(REMOVE_RECURSE ${work})
    message(FATAL_ERROR "${what} failed (${status}):\n${out}\n${err}")
  endif()
endfunction()

function(expect_usage program)
  execute_process(COMMAND ${program} RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL 2 OR NOT err MATCHES "usage: ")
    file(REMOVE_RECURSE ${work})
    message(FATAL_ERROR "${program} without arguments: exit ${status}, stderr:\n${err}")
  endif()
endfunction()

run("cmake --install" ${CMAKE_COMMAND} --install ${ORBIT_BUILD_DIR} --prefix ${work}/prefix)
foreach(file lib/liborbit_client.a include/client/enroller.h include/orbit/v1/models.pb.h
    lib/cmake/OrbitClient/OrbitClientConfig.cmake lib/pkgconfig/orbit-client.pc)
  if(NOT EXISTS ${work}/prefix/${file})
    file(REMOVE_RECURSE ${work})
    message(FATAL_ERROR "not installed: ${file}")
  endif()
endforeach()

# CMake: find_package(OrbitClient) from the prefix, a copy of the example outside the tree.
file(COPY ${ORBIT_SOURCE_DIR}/examples/capture_client DESTINATION ${work})
run("configuring the example" ${CMAKE_COMMAND} -S ${work}/capture_client -B ${work}/build
  -DCMAKE_PREFIX_PATH=${work}/prefix -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS=${FLAGS}"
  "-DCMAKE_EXE_LINKER_FLAGS=${FLAGS}")
run("building the example" ${CMAKE_COMMAND} --build ${work}/build)
expect_usage(${work}/build/orbit_capture_client)

# pkg-config and the compiler alone.
set(ENV{PKG_CONFIG_PATH} ${work}/prefix/lib/pkgconfig)
execute_process(COMMAND pkg-config --cflags --libs orbit-client RESULT_VARIABLE status
  OUTPUT_VARIABLE flags ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT status EQUAL 0)
  file(REMOVE_RECURSE ${work})
  message(FATAL_ERROR "pkg-config orbit-client: ${err}")
endif()
separate_arguments(flags UNIX_COMMAND "${flags} ${FLAGS}")
run("compiling the example with pkg-config" ${CXX} -o ${work}/example_pc
  ${work}/capture_client/main.cc ${flags})
expect_usage(${work}/example_pc)

file(REMOVE_RECURSE ${work})
