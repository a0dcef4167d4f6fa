// The precompiled headers of the tests (test/CMakeLists.txt) are built with this file.
