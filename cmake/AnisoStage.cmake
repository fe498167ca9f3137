# One library and one executable per stage: aniso_<stage> and aniso-<stage>.
# A stage whose computation has not landed yet has no sources: its library is
# an INTERFACE library over aniso_common until its issue adds code.
function(aniso_add_stage stage)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBRARIES" ${ARGN})
  if(ARG_SOURCES)
    add_library(aniso_${stage} STATIC ${ARG_SOURCES})
    target_link_libraries(aniso_${stage} PUBLIC aniso_common ${ARG_LIBRARIES} PRIVATE aniso_warnings)
  else()
    add_library(aniso_${stage} INTERFACE)
    target_link_libraries(aniso_${stage} INTERFACE aniso_common ${ARG_LIBRARIES})
  endif()
  add_executable(aniso-${stage} main.cpp)
  target_link_libraries(aniso-${stage} PRIVATE aniso_${stage} aniso_warnings)
endfunction()
