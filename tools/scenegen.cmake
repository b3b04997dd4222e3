# Deterministic scene generators (rad_scenegen) for tests and benchmarks, and the rad-gen CLI.
add_library(rad_scenegen STATIC ${CMAKE_CURRENT_LIST_DIR}/scenegen/scenegen.cpp
                                 ${CMAKE_CURRENT_LIST_DIR}/scenegen/model_pairs.cpp)
target_include_directories(rad_scenegen PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(rad_scenegen PUBLIC rad_scene rad_hierarchy PRIVATE rad_warnings rad_optimize)

add_executable(rad-gen ${CMAKE_CURRENT_LIST_DIR}/gen_scene.cpp)
target_link_libraries(rad-gen PRIVATE rad_scenegen CLI11::CLI11 fmt::fmt rad_warnings)

add_executable(rad-tessellate ${CMAKE_CURRENT_LIST_DIR}/tessellate.cpp)
target_link_libraries(rad-tessellate PRIVATE rad_scenegen CLI11::CLI11 fmt::fmt rad_warnings)
