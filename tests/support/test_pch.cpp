// The source that builds the tests' shared precompiled header (tests/CMakeLists.txt); it
// defines nothing.
