#pragma once
// Headers nearly every test file parses: compiled once (irgs_test_pch) and reused by every test
// program (irgs_add_test), instead of once per test file. Test files still include what they
// use; this only makes those includes cheap.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>
