# orbit_describe_images on the CEDD conformance set (the shared data's cedd-conformance/, or
# $ORBIT_DATA's), once on this CPU's fastest hot loops and once with --portable: both print one
# line per image and variant, and the same lines (docs/design.md#hot-loops).
#   cmake -DPROGRAM=build/orbit_describe_images -DDATA=../shared/data -P describe_images_test.cmake
if(DEFINED ENV{ORBIT_DATA})
  set(DATA $ENV{ORBIT_DATA})
endif()
set(folder ${DATA}/cedd-conformance)
if(NOT IS_DIRECTORY ${folder})
  message(FATAL_ERROR "the conformance set is not at ${folder} (set ORBIT_DATA)")
endif()

function(describe out)
  execute_process(COMMAND ${PROGRAM} ${ARGN} ${folder} RESULT_VARIABLE status
    OUTPUT_VARIABLE lines ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${PROGRAM} ${ARGN} ${folder}: exit ${status}\n${err}")
  endif()
  set(${out} "${lines}" PARENT_SCOPE)
endfunction()

describe(fastest)
describe(portable --portable)

file(GLOB_RECURSE images ${folder}/*.png ${folder}/*.jpg ${folder}/*.jpeg)
list(LENGTH images image_count)
string(REGEX MATCHALL "\n" newlines "${fastest}")
list(LENGTH newlines line_count)
math(EXPR expected "${image_count} * 6")  # every variant: lire, full, robust, hsv-hog, -layout, soft
if(image_count EQUAL 0 OR NOT line_count EQUAL expected)
  message(FATAL_ERROR "${line_count} lines for ${image_count} images, expected ${expected}")
endif()
if(NOT fastest STREQUAL portable)
  message(FATAL_ERROR "the fastest and the portable hot loops describe the conformance set "
    "differently")
endif()

# A folder that is not there: usage, exit 2.
execute_process(COMMAND ${PROGRAM} ${folder}/not-a-folder RESULT_VARIABLE status
  ERROR_VARIABLE err)
if(NOT status EQUAL 2 OR NOT err MATCHES "is not a folder")
  message(FATAL_ERROR "a missing folder: exit ${status}, stderr:\n${err}")
endif()
