// The constants header proved against independent integer arithmetic, and the kernel's
// properties checked against its definition.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "stereo/constants.hpp"
#include "stereo/pipeline.hpp"

namespace stereo {
namespace {

TEST(Constants, Mean9IsRoundedDivisionOverTheWholeRange) {
    for (std::uint32_t sum = 0; sum <= 9U * fx::kAggMax; ++sum) {
        const double exact = sum / 9.0;
        ASSERT_EQ(fx::mean9(sum), static_cast<std::uint32_t>(std::floor(exact + 0.5))) << sum;
    }
}

TEST(Constants, Div13IsRoundedDivisionOverTheWholeRange) {
    for (std::uint32_t v = 0; v <= static_cast<std::uint32_t>(fx::kAggMax); ++v) {
        const double exact = v / 1.3;
        ASSERT_EQ(fx::div13(v), static_cast<std::uint32_t>(std::floor(exact + 0.5))) << v;
    }
}

TEST(Constants, WidthsHoldTheirMaxima) {
    EXPECT_EQ(fx::kCostMax, 765);
    EXPECT_LT(fx::kCostMax, 1 << fx::kCostBits);
    EXPECT_LT(fx::kAggMax, 1 << fx::kAggBits);
    EXPECT_EQ(fx::kAggShift + fx::kAggFracBits, 2 * fx::kKernelBits);
}

TEST(Kernel, SumsToPowerOfTwoSymmetricAndCloseToGaussian) {
    for (int window = 1; window <= fx::kMaxWindow; window += 2) {
        for (const double sigma : {0.5, 1.0, 2.0, 3.0, 5.0, 10.0}) {
            const auto taps = gaussian_kernel(window, sigma);
            ASSERT_EQ(static_cast<int>(taps.size()), window);
            EXPECT_EQ(std::accumulate(taps.begin(), taps.end(), 0), fx::kKernelSum);
            const int r = window / 2;
            double total = 0.0;
            for (int i = -r; i <= r; ++i) {
                total += std::exp(-(i * i) / (2 * sigma * sigma));
            }
            for (int i = 0; i < window; ++i) {
                EXPECT_GE(taps[i], 0);
                EXPECT_EQ(taps[i], taps[window - 1 - i]) << "asymmetric";
                const double ideal =
                    fx::kKernelSum * std::exp(-((i - r) * (i - r)) / (2 * sigma * sigma)) / total;
                // All taps are one rounded scaled Gaussian; the scale differs slightly from
                // 2^kKernelBits / sum(g) and the centre may give back one unit.
                EXPECT_LE(std::abs(taps[i] - ideal), 1.5)
                    << "window " << window << " sigma " << sigma << " tap " << i;
            }
        }
    }
}

TEST(Kernel, TwoDimensionalWeightIsGaussianOfEuclideanDistance) {
    // k[i]*k[j] ~ exp(-(i^2 + j^2) / 2 sigma^2): rows and columns of the outer product are all
    // scaled copies of one Gaussian, so the weight depends on the distance to the centre only
    // (up to the integer rounding of the taps: each tap is within one unit of ~36 of its ideal
    // value, so a product of two is within about 2 * 1/36 = 6% of the ideal weight).
    const auto taps = gaussian_kernel(11, 3.0);
    const int r = 5;
    const double centre = double(taps[r]) * taps[r];
    for (int j = -r; j <= r; ++j) {
        for (int i = -r; i <= r; ++i) {
            const double weight = double(taps[i + r]) * taps[j + r] / centre;
            const double ideal = std::exp(-(i * i + j * j) / (2 * 9.0));
            EXPECT_NEAR(weight, ideal, 0.06) << i << "," << j;
        }
    }
}

TEST(Kernel, RejectsBadWindowsAndSigmas) {
    EXPECT_THROW(gaussian_kernel(0, 1.0), std::invalid_argument);
    EXPECT_THROW(gaussian_kernel(4, 1.0), std::invalid_argument);
    EXPECT_THROW(gaussian_kernel(fx::kMaxWindow + 2, 1.0), std::invalid_argument);
    EXPECT_THROW(gaussian_kernel(11, -1.0), std::invalid_argument);
    EXPECT_THROW(gaussian_kernel(11, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace stereo
