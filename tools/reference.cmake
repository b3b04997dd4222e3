# The independent radiosity reference (tools/reference): a path tracer (rad_reference) at points
# and through a camera's pixels, the comparison of rad's output against its CSV files and
# images (rad_reference_compare), and rad-reference.
set(rad_reference_dir ${CMAKE_CURRENT_LIST_DIR}/reference)

add_library(rad_reference_compare STATIC
  ${rad_reference_dir}/reference_set.cpp
  ${rad_reference_dir}/compare.cpp
  ${rad_reference_dir}/image_compare.cpp
  ${rad_reference_dir}/ply_reader.cpp)
target_include_directories(rad_reference_compare PUBLIC ${CMAKE_CURRENT_LIST_DIR})
target_link_libraries(rad_reference_compare PUBLIC rad_hierarchy PRIVATE rad_scene rad_warnings rad_optimize)

add_library(rad_reference STATIC
  ${rad_reference_dir}/ray_scene.cpp
  ${rad_reference_dir}/buried_points.cpp
  ${rad_reference_dir}/reference_points.cpp
  ${rad_reference_dir}/path_tracer.cpp
  ${rad_reference_dir}/camera_reference.cpp)
# rad_export for rad's camera model (export/camera.h), so the reference's pixels are rad's.
target_link_libraries(rad_reference PUBLIC rad_reference_compare rad_hierarchy rad_export TBB::tbb
                                    PRIVATE embree rad_warnings rad_optimize)

add_executable(rad-reference ${rad_reference_dir}/main.cpp)
target_link_libraries(rad-reference PRIVATE rad_reference CLI11::CLI11 fmt::fmt rad_warnings
                                            rad_optimize)
