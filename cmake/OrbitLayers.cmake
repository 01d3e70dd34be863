# Layers (docs/design.md#layers). Every folder of code is one layer and one library target, which
# links only the layers below it. orbit_layer() records a target as the layer of a folder; the
# build then refuses any include of a layer's header from a folder whose target does not link
# that layer, directly or through the layers it links (cmake/check_layers.cmake). The layer
# table is the link graph itself: there is no second list to keep in step.

# orbit_layer(TARGET FOLDER [INCLUDE_PREFIX PREFIX]): TARGET is the layer of FOLDER (relative to
# the source tree). Its headers are included as "PREFIX..." (default "FOLDER/").
function(orbit_layer target folder)
  cmake_parse_arguments(PARSE_ARGV 2 arg "" "INCLUDE_PREFIX" "")
  if(NOT arg_INCLUDE_PREFIX)
    set(arg_INCLUDE_PREFIX "${folder}/")
  endif()
  set_property(GLOBAL APPEND PROPERTY ORBIT_LAYERS ${target})
  set_property(TARGET ${target} PROPERTY ORBIT_LAYER_FOLDER ${folder})
  set_property(TARGET ${target} PROPERTY ORBIT_LAYER_INCLUDE_PREFIX ${arg_INCLUDE_PREFIX})
endfunction()

# The layers `target` links, directly or through others, itself included, into `out`.
function(_orbit_layers_below target out)
  set(seen ${target})
  set(queue ${target})
  while(queue)
    list(POP_FRONT queue current)
    get_target_property(linked ${current} LINK_LIBRARIES)
    get_target_property(interface ${current} INTERFACE_LINK_LIBRARIES)
    foreach(library IN LISTS linked interface)
      if(TARGET ${library} AND NOT library IN_LIST seen)
        list(APPEND seen ${library})
        list(APPEND queue ${library})
      endif()
    endforeach()
  endwhile()
  set(${out} ${seen} PARENT_SCOPE)
endfunction()

# Called once every target exists: writes the table (one line per layer: folder|prefix|the
# prefixes it may include) and the target orbit_layer_check, which every layer's build waits for;
# and orbit_libraries, which builds every layer.
function(orbit_check_layers)
  get_property(layers GLOBAL PROPERTY ORBIT_LAYERS)
  set(table "")
  foreach(layer IN LISTS layers)
    _orbit_layers_below(${layer} below)
    set(allowed "")
    foreach(library IN LISTS below)
      if(library IN_LIST layers)
        get_target_property(prefix ${library} ORBIT_LAYER_INCLUDE_PREFIX)
        list(APPEND allowed ${prefix})
      endif()
    endforeach()
    get_target_property(folder ${layer} ORBIT_LAYER_FOLDER)
    get_target_property(prefix ${layer} ORBIT_LAYER_INCLUDE_PREFIX)
    list(JOIN allowed "," allowed)
    string(APPEND table "${layer}|${folder}|${prefix}|${allowed}\n")
  endforeach()
  set(table_file ${PROJECT_BINARY_DIR}/orbit_layers.txt)
  file(WRITE ${table_file} "${table}")
  add_custom_target(orbit_layer_check
    COMMAND ${CMAKE_COMMAND} -DTABLE=${table_file} -DSOURCE_DIR=${PROJECT_SOURCE_DIR}
      -P ${PROJECT_SOURCE_DIR}/cmake/check_layers.cmake
    COMMENT "Checking that every include points down a layer"
    VERBATIM)
  foreach(layer IN LISTS layers)
    add_dependencies(${layer} orbit_layer_check)
  endforeach()
  # Every layer's library and nothing else (scripts/test.sh's thread safety build).
  add_custom_target(orbit_libraries)
  add_dependencies(orbit_libraries ${layers})
endfunction()
