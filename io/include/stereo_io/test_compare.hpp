// GoogleTest comparisons shared by tests/ and testbench/ (header-only, stereo_test_support; the
// includer links GoogleTest): volumes value by value and maps pixel by pixel, each failure naming
// how many values differ and the first five.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <string_view>

#include "stereo/dsi.hpp"
#include "stereo/image.hpp"
#include "stereo/validated.hpp"

namespace stereo::test {

// Counts mismatches and keeps the descriptions of the first few.
class Mismatches {
  public:
    // One mismatch; `describe()` (a string) is only called for the ones listed.
    template <typename Describe>
    void add(Describe&& describe) {
        if (count_++ < kListed) {
            listed_ += ' ';
            listed_ += describe();
            listed_ += ';';
        }
    }

    // Success when there were none; otherwise "<count> of <total> <what> differ, first: ...".
    ::testing::AssertionResult result(std::size_t total, std::string_view what) const {
        if (count_ == 0) {
            return ::testing::AssertionSuccess();
        }
        return ::testing::AssertionFailure()
               << count_ << " of " << total << " " << what << " differ, first:" << listed_;
    }

  private:
    static constexpr std::size_t kListed = 5;
    std::size_t count_ = 0;
    std::string listed_;
};

// Two maps of one raster (width, height, index(x, y)), pixel by pixel in raster order:
// `differs(i)` tells whether pixel i differs, `describe(map, i)` what a map holds there.
template <typename Map, typename Differs, typename Describe>
::testing::AssertionResult same_pixels(const Map& expected, const Map& actual, Differs&& differs,
                                       Describe&& describe) {
    if (expected.width != actual.width || expected.height != actual.height) {
        return ::testing::AssertionFailure()
               << "sizes differ: " << expected.width << "x" << expected.height << " expected, "
               << actual.width << "x" << actual.height << " actual";
    }
    Mismatches mismatches;
    for (int y = 0; y < expected.height; ++y) {
        for (int x = 0; x < expected.width; ++x) {
            const std::size_t i = expected.index(x, y);
            if (differs(i)) {
                mismatches.add([&] {
                    return "(x=" + std::to_string(x) + ", y=" + std::to_string(y) + "): expected " +
                           describe(expected, i) + ", actual " + describe(actual, i);
                });
            }
        }
    }
    return mismatches.result(static_cast<std::size_t>(expected.width) * expected.height, "pixels");
}

// Planes [0, planes) of two volumes of one width and height, value by value in stream order
// (y, x, d).
inline ::testing::AssertionResult same_volume(const Dsi& expected, const Dsi& actual, int planes) {
    if (expected.width() != actual.width() || expected.height() != actual.height() ||
        expected.ndisp() < planes || actual.ndisp() < planes) {
        return ::testing::AssertionFailure() << "volume shapes differ";
    }
    Mismatches mismatches;
    for (int y = 0; y < expected.height(); ++y) {
        for (int x = 0; x < expected.width(); ++x) {
            for (int d = 0; d < planes; ++d) {
                const int want = expected.at(x, y, d);
                const int got = actual.at(x, y, d);
                if (want != got) {
                    mismatches.add([&] {
                        return "(x=" + std::to_string(x) + ", y=" + std::to_string(y) +
                               ", d=" + std::to_string(d) + "): expected " + std::to_string(want) +
                               ", actual " + std::to_string(got);
                    });
                }
            }
        }
    }
    return mismatches.result(expected.plane_size() * static_cast<std::size_t>(planes), "values");
}

// Two volumes of the same shape, every value.
inline ::testing::AssertionResult same_volume(const Dsi& expected, const Dsi& actual) {
    if (expected.ndisp() != actual.ndisp()) {
        return ::testing::AssertionFailure() << "volume shapes differ";
    }
    return same_volume(expected, actual, expected.ndisp());
}

// The disparity and the valid flag of every pixel.
inline ::testing::AssertionResult same_map(const DisparityMap& expected,
                                           const DisparityMap& actual) {
    return same_pixels(
        expected, actual,
        [&](std::size_t i) {
            return expected.disparity[i] != actual.disparity[i] ||
                   expected.valid[i] != actual.valid[i];
        },
        [](const DisparityMap& map, std::size_t i) {
            return "d=" + std::to_string(map.disparity[i]) +
                   " valid=" + std::to_string(map.valid[i]);
        });
}

// Stage 6's output of every pixel, exactly: fixed disparity, reason and certainty.
inline ::testing::AssertionResult same_validated(const ValidatedDisparity& expected,
                                                 const ValidatedDisparity& actual) {
    return same_pixels(
        expected, actual,
        [&](std::size_t i) {
            return expected.fixed[i] != actual.fixed[i] || expected.reason[i] != actual.reason[i] ||
                   expected.certainty[i] != actual.certainty[i];
        },
        [](const ValidatedDisparity& map, std::size_t i) {
            return "fixed=" + std::to_string(map.fixed[i]) +
                   " reason=" + std::to_string(map.reason[i]) +
                   " certainty=" + std::to_string(map.certainty[i]);
        });
}

}  // namespace stereo::test
