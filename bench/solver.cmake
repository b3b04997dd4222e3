# The solver at work (one shot, raw replay of its rays, refinement, Cornell solve) and set-up
# costs (hierarchy, Embree BVH, grids, solver state); tools/bench runs them and prints the table.
rad_add_bench(solver_bench
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/solver_bench.cpp
  LIBS rad_solver rad_scene rad_scenegen TBB::tbb)
target_compile_definitions(solver_bench PRIVATE RAD_SOURCE_DIR="${PROJECT_SOURCE_DIR}")

rad_add_bench(build_bench
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/build_bench.cpp
  LIBS rad_solver rad_scenegen TBB::tbb)

rad_add_bench(model_pairs_bench
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/model_pairs_bench.cpp
  LIBS rad_run rad_scenegen TBB::tbb)
target_compile_definitions(model_pairs_bench PRIVATE RAD_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
