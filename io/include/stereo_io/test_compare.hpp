// GoogleTest comparisons shared by tests/ and testbench/ (header-only, stereo_test_support; the
// includer links GoogleTest).
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "stereo/validated.hpp"

namespace stereo::test {

// Stage 6's output of every pixel, exactly: fixed disparity, reason and certainty. On failure
// the number of differing pixels and the first five.
inline ::testing::AssertionResult same_validated(const ValidatedDisparity& expected,
                                                 const ValidatedDisparity& actual) {
    if (expected.width != actual.width || expected.height != actual.height) {
        return ::testing::AssertionFailure()
               << "sizes differ: " << expected.width << "x" << expected.height << " expected, "
               << actual.width << "x" << actual.height << " actual";
    }
    std::size_t mismatches = 0;
    std::string first;
    for (int y = 0; y < expected.height; ++y) {
        for (int x = 0; x < expected.width; ++x) {
            const auto i = expected.index(x, y);
            if ((expected.fixed[i] != actual.fixed[i] || expected.reason[i] != actual.reason[i] ||
                 expected.certainty[i] != actual.certainty[i]) &&
                mismatches++ < 5) {
                first += " (x=" + std::to_string(x) + ", y=" + std::to_string(y) +
                         "): expected fixed=" + std::to_string(expected.fixed[i]) +
                         " reason=" + std::to_string(expected.reason[i]) +
                         " certainty=" + std::to_string(expected.certainty[i]) +
                         ", actual fixed=" + std::to_string(actual.fixed[i]) +
                         " reason=" + std::to_string(actual.reason[i]) +
                         " certainty=" + std::to_string(actual.certainty[i]) + ";";
            }
        }
    }
    if (mismatches == 0) {
        return ::testing::AssertionSuccess();
    }
    return ::testing::AssertionFailure()
           << mismatches << " of " << expected.fixed.size() << " pixels differ, first:" << first;
}

}  // namespace stereo::test
