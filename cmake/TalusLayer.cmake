# talus_add_layer(NAME SOURCES ... DEPENDS ...): one library per layer with
# its public headers under <layer>/include/talus/<layer>/ and alias talus::NAME.
function(talus_add_layer name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPENDS;PRIVATE_DEPENDS" ${ARGN})
  if(NOT ARG_SOURCES)
    # A layer whose code has not landed yet still fixes its place in the
    # dependency order (see README, "Layout").
    add_library(talus_${name} INTERFACE)
    target_link_libraries(talus_${name} INTERFACE ${ARG_PUBLIC_DEPENDS})
    set_target_properties(talus_${name} PROPERTIES EXPORT_NAME ${name})
    add_library(talus::${name} ALIAS talus_${name})
    return()
  endif()
  add_library(talus_${name} ${ARG_SOURCES})
  add_library(talus::${name} ALIAS talus_${name})
  set_target_properties(talus_${name} PROPERTIES EXPORT_NAME ${name} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(talus_${name} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(talus_${name} PUBLIC ${ARG_PUBLIC_DEPENDS}
                                      PRIVATE ${ARG_PRIVATE_DEPENDS} $<BUILD_INTERFACE:talus_warnings>)
  talus_use_pch(talus_${name} lib)
  install(DIRECTORY include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endfunction()
