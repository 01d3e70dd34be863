# cmake/check_layers.cmake refuses an include that points up a layer and passes the real tree:
#   cmake -DCHECK=cmake/check_layers.cmake -DTABLE=build/orbit_layers.txt -DSOURCE_DIR=. -P ...
# A made-up tree of two layers, "low" below "high": high may include low; low including high is
# refused, with the file, the header and the missing link named.
cmake_minimum_required(VERSION 3.25)
string(RANDOM LENGTH 10 suffix)
set(work /tmp/orbit-layers-test-${suffix})
file(REMOVE_RECURSE ${work})
file(WRITE ${work}/table.txt "low|low|low/|low/\nhigh|high|high/|high/,low/\n")
file(WRITE ${work}/low/a.h "#pragma once\n#include <vector>\n")
file(WRITE ${work}/high/b.h "#pragma once\n#include \"low/a.h\"\n#include \"third/party.h\"\n")

function(check table source_dir result_out error_out)
  execute_process(COMMAND ${CMAKE_COMMAND} -DTABLE=${table} -DSOURCE_DIR=${source_dir} -P ${CHECK}
    RESULT_VARIABLE result ERROR_VARIABLE error)
  set(${result_out} ${result} PARENT_SCOPE)
  set(${error_out} "${error}" PARENT_SCOPE)
endfunction()

function(fail message)
  file(REMOVE_RECURSE ${work})
  message(FATAL_ERROR "${message}")
endfunction()

check(${work}/table.txt ${work} result error)
if(NOT result EQUAL 0)
  fail("downward includes refused:\n${error}")
endif()

file(WRITE ${work}/low/c.cc "#include \"low/a.h\"\n#include \"high/b.h\"\n")
check(${work}/table.txt ${work} result error)
if(result EQUAL 0 OR NOT error MATCHES "low/c.cc includes \"high/b.h\", but low does not link high")
  fail("an upward include passed (exit ${result}):\n${error}")
endif()
if(error MATCHES "low/a.h\"," OR error MATCHES "third/party")
  fail("a downward or third-party include reported:\n${error}")
endif()

check(${TABLE} ${SOURCE_DIR} result error)
if(NOT result EQUAL 0)
  fail("the tree has includes that point up:\n${error}")
endif()
file(REMOVE_RECURSE ${work})
