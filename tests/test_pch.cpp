// The object that builds the precompiled header all test programs reuse (tests/CMakeLists.txt).
#include "test_pch.hpp"
