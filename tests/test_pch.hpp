#pragma once
// Precompiled into every test program (tests/CMakeLists.txt): what nearly every test includes.
#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Core>

#include "core/error.hpp"
