# Generates C++ types for Fast DDS (fastddsgen, one call for all files: it is a slow Java program)
# and C types for Cyclone DDS (idlc) at build time into the build tree. Nothing generated is committed.
#
#   slam_generate_idl(FILES a.idl b.idl ...)
#
# Creates: slam_idl_fastdds (include <slam/fastdds/NAME.h>, <slam/fastdds/NAMEPubSubTypes.h>)
#          slam_idl_cyclone (include <slam/cyclone/NAME.h>)
find_program(FASTDDSGEN fastddsgen REQUIRED)
find_program(IDLC idlc HINTS /usr/bin REQUIRED)

function(slam_generate_idl)
  cmake_parse_arguments(ARG "" "" "FILES" ${ARGN})
  set(fast_dir ${CMAKE_BINARY_DIR}/generated/fastdds/slam/fastdds)
  set(cyc_dir ${CMAKE_BINARY_DIR}/generated/cyclone/slam/cyclone)
  file(MAKE_DIRECTORY ${fast_dir} ${cyc_dir})

  set(idl_abs "")
  set(fast_src "")
  set(cyc_src "")
  foreach(idl ${ARG_FILES})
    get_filename_component(abs ${idl} ABSOLUTE)
    get_filename_component(name ${idl} NAME_WE)
    list(APPEND idl_abs ${abs})
    list(APPEND fast_src ${fast_dir}/${name}.cxx ${fast_dir}/${name}PubSubTypes.cxx)
    list(APPEND cyc_src ${cyc_dir}/${name}.c)
    add_custom_command(
      OUTPUT ${cyc_dir}/${name}.c ${cyc_dir}/${name}.h
      COMMAND ${IDLC} -Wno-implicit-extensibility -I ${CMAKE_SOURCE_DIR}/idl ${abs}
      WORKING_DIRECTORY ${cyc_dir}
      DEPENDS ${abs}
      COMMENT "idlc ${name}.idl"
      VERBATIM)
  endforeach()
  # Any IDL change regenerates all Fast DDS files (includes cross files; one call is cheapest).
  add_custom_command(
    OUTPUT ${fast_src}
    COMMAND ${FASTDDSGEN} -replace -d ${fast_dir} -I ${CMAKE_SOURCE_DIR}/idl ${idl_abs} > fastddsgen.log
    WORKING_DIRECTORY ${CMAKE_BINARY_DIR}/generated
    DEPENDS ${idl_abs}
    COMMENT "fastddsgen ${ARG_FILES}"
    VERBATIM)

  add_library(slam_idl_fastdds STATIC ${fast_src})
  target_include_directories(slam_idl_fastdds SYSTEM PUBLIC ${CMAKE_BINARY_DIR}/generated/fastdds)
  target_link_libraries(slam_idl_fastdds PUBLIC fastrtps fastcdr)
  set_target_properties(slam_idl_fastdds PROPERTIES POSITION_INDEPENDENT_CODE ON)

  add_library(slam_idl_cyclone STATIC ${cyc_src})
  target_include_directories(slam_idl_cyclone SYSTEM PUBLIC ${CMAKE_BINARY_DIR}/generated/cyclone)
  target_link_libraries(slam_idl_cyclone PUBLIC CycloneDDS::ddsc)
endfunction()
