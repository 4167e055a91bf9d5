# terrasynth_headless_view: UPDATE + CULL of a scene without a graphics context (headless_view.h),
# for the plugin's and the editor's tests and for bench/tiles_bench. bench/ is configured before
# tests/, and either may be left out, so both include this file and the first one defines it.
if(NOT TARGET terrasynth_headless_view)
  find_package(OpenSceneGraph REQUIRED COMPONENTS osgUtil)
  add_library(terrasynth_headless_view STATIC ${CMAKE_CURRENT_LIST_DIR}/headless_view.cpp)
  target_include_directories(terrasynth_headless_view PUBLIC ${CMAKE_CURRENT_LIST_DIR})
  target_include_directories(terrasynth_headless_view SYSTEM PUBLIC ${OPENSCENEGRAPH_INCLUDE_DIRS})
  target_link_libraries(terrasynth_headless_view PUBLIC ${OPENSCENEGRAPH_LIBRARIES})
endif()
