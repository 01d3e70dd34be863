# The installed device library, as an application outside Orbit's tree uses it:
# installs the build into a fresh prefix under /tmp, builds examples/capture_client there with
# find_package(OrbitClient) and again with the compiler and `pkg-config --cflags --libs
# orbit-client` alone, and runs both builds (no arguments: usage, exit 2). The device library
# carries no server part (docs/design.md#layers): the prefix's lib/ holds exactly the device's
# libraries, and the example, linked statically against them, defines no symbol of the view
# index, the engines, the decision rules or the model store (nm).
#   cmake -DORBIT_BUILD_DIR=build -DORBIT_SOURCE_DIR=. -DCXX=c++ [-DNM=nm] [-DFLAGS=...]
#     -P build_example.cmake
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

# The device's libraries and no others: a library added to orbit_client's links (an index, an
# engine) is installed with it and fails here.
set(device_libraries liborbit_api.a liborbit_base.a liborbit_client.a liborbit_descriptor.a
  liborbit_model.a liborbit_proto.a)
file(GLOB installed RELATIVE ${work}/prefix/lib ${work}/prefix/lib/*.a)
list(SORT installed)
if(NOT installed STREQUAL device_libraries)
  file(REMOVE_RECURSE ${work})
  message(FATAL_ERROR "the installed libraries are ${installed}, expected the device's alone: "
    "${device_libraries}")
endif()

# CMake: find_package(OrbitClient) from the prefix, a copy of the example outside the tree.
file(COPY ${ORBIT_SOURCE_DIR}/examples/capture_client DESTINATION ${work})
run("configuring the example" ${CMAKE_COMMAND} -S ${work}/capture_client -B ${work}/build
  -DCMAKE_PREFIX_PATH=${work}/prefix -DCMAKE_BUILD_TYPE=Release "-DCMAKE_CXX_FLAGS=${FLAGS}"
  "-DCMAKE_EXE_LINKER_FLAGS=${FLAGS}")
run("building the example" ${CMAKE_COMMAND} --build ${work}/build)
expect_usage(${work}/build/orbit_capture_client)

# What the example links of Orbit: nothing of the server's side, even through a library the
# device does link (a conversion that names a view index's objects pulls the index in).
if(NOT NM)
  set(NM nm)
endif()
execute_process(COMMAND ${NM} -C --defined-only ${work}/build/orbit_capture_client
  RESULT_VARIABLE status OUTPUT_VARIABLE symbols ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  file(REMOVE_RECURSE ${work})
  message(FATAL_ERROR "nm of the example failed (${status}): ${err}")
endif()
string(REGEX MATCHALL
  "orbit::(ViewIndex|IndexedObject|ViewBins|SectorViews|AssessEnrollment|FrameUpdate|RecognitionEngine|WindowedEngine|OrientationHmm|HoughVoter|ProductPipeline|ModelStore|SqliteModelStore|PostgresModelStore)[A-Za-z]*"
  server_symbols "${symbols}")
if(server_symbols)
  list(REMOVE_DUPLICATES server_symbols)
  file(REMOVE_RECURSE ${work})
  message(FATAL_ERROR "the example links the server's side: ${server_symbols}")
endif()

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
