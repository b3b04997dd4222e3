# Shadow-ray throughput per visibility backend × scene × single/packet (Google Benchmark).
rad_add_bench(visibility_bench
  SOURCES ${CMAKE_CURRENT_LIST_DIR}/visibility_bench.cpp
  LIBS rad_visibility rad_scenegen)
