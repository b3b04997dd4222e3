// The object the precompiled test headers are made for (tests/CMakeLists.txt, rad_test_headers).
