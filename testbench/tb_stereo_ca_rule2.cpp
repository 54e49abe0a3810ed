// stereo_ca_rule2 against stereo::ca_rule2: every value of every pixel and disparity, for the
// rule-1 output of a random pair (what rule 2 sees in the pipeline), smooth random planes on
// which the count of agreeing neighbours straddles the threshold of 7, small values (the strict
// 2|n - c| < c boundary), values near the maximum (the widest product), CA off (identity), odd
// and tiny frames (borders, zero padding never agrees), random clock enables, frames back to back.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "ca_rule_bench.hpp"  // first: it includes the Verilator runtime headers quietly

#include "Vstereo_ca_rule2.h"
#include "stereo/pipeline.hpp"

namespace stereo::tb {
namespace {

constexpr int kDisparities = table::verilated("Vstereo_ca_rule2").params.ndisp;

// Rule 1 applied to the aggregate of a random pair with true disparity 3.
Dsi pair_rule1(int width, int height, std::mt19937& rng) {
    return ca_rule1(aggregate(pair_cost(width, height, kDisparities, 3, rng),
                              gaussian_kernel(5, fx::kDefaultSigma)));
}

// Every plane a base value with per-pixel noise whose amplitude changes from plane to plane and
// across the image: where it is small nearly all 8 neighbours agree and the rule fires, where it
// is large the count falls below 7; in between it straddles the threshold.
Dsi smooth_volume(int width, int height, std::mt19937& rng) {
    Dsi volume(width, height, kDisparities);
    std::uniform_int_distribution<int> base_value(200, fx::kAggMax);
    std::uniform_real_distribution<double> amplitude(0.3, 1.4);
    std::uniform_real_distribution<double> unit(-0.5, 0.5);
    for (int d = 0; d < kDisparities; ++d) {
        const int base = base_value(rng);
        const double left_amplitude = amplitude(rng);
        const double right_amplitude = amplitude(rng);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                // The amplitude ramps across the row, so a plane holds several regimes.
                const double t = width > 1 ? static_cast<double>(x) / (width - 1) : 0.0;
                const double spread = base * ((1 - t) * left_amplitude + t * right_amplitude);
                const int value = base + static_cast<int>(spread * unit(rng));
                volume.at(x, y, d) = static_cast<Dsi::Value>(std::clamp(value, 0, fx::kAggMax));
            }
        }
    }
    return volume;
}

struct Rule2 {
    using Model = Vstereo_ca_rule2;
    static constexpr const char* kPrefix = "Vstereo_ca_rule2";
    static constexpr const char* kName = "stereo_ca_rule2";
    static constexpr bool kHasNdisp = false;  // rule 2 does not look across planes
    static constexpr const char* kStructuredName = "smooth";
    static constexpr int kSmallLow = 1;  // 1..5: agreement decided at 2|n - c| == c, count near 7
    static constexpr int kSmallHigh = 5;
    static Dsi apply(const Dsi& volume) { return ca_rule2(volume); }
    static Dsi pair(int width, int height, std::mt19937& rng) {
        return pair_rule1(width, height, rng);
    }
    static Dsi structured(int width, int height, std::mt19937& rng) {
        return smooth_volume(width, height, rng);
    }
};

using Bench = CaRuleBench<Rule2>;
using Case = Bench::Case;
using Input = CaInput;

class Volumes : public ::testing::TestWithParam<Case> {};

TEST_P(Volumes, EveryValueEqualsTheModel) {
    Bench::check_case(GetParam());
}

INSTANTIATE_TEST_SUITE_P(
    Rule2, Volumes,
    ::testing::Values(Case{64, 48, Input::kPair, kDisparities, true, 0.0},
                      Case{64, 48, Input::kStructured, kDisparities, true, 0.3},
                      Case{64, 48, Input::kSmallValues, kDisparities, true, 0.2},
                      Case{64, 48, Input::kNearMaximum, kDisparities, true, 0.2},
                      Case{37, 23, Input::kStructured, kDisparities, true, 0.25},
                      Case{37, 23, Input::kPair, kDisparities, true, 0.1},
                      Case{13, 9, Input::kStructured, kDisparities, true, 0.5},
                      Case{13, 9, Input::kSmallValues, kDisparities, true, 0.3},
                      Case{3, 3, Input::kNearMaximum, kDisparities, true, 0.3},
                      Case{3, 3, Input::kStructured, kDisparities, true, 0.0},
                      // CA off: the identity, on every bit of the 14
                      Case{64, 48, Input::kFull14Bits, kDisparities, false, 0.3},
                      Case{13, 9, Input::kStructured, kDisparities, false, 0.2},
                      Case{3, 3, Input::kFull14Bits, kDisparities, false, 0.2}),
    Bench::case_name);

// The smooth inputs must make the test strong: the rule has to fire on many cells, not all.
TEST(Rule2Inputs, SmoothVolumesMakeTheRuleFireOnPartOfTheCells) {
    std::mt19937 rng(test_seed());
    const Dsi input = smooth_volume(64, 48, rng);
    const double fired = changed_fraction(input, ca_rule2(input));
    EXPECT_GT(fired, 0.15);
    EXPECT_LT(fired, 0.85);
}

TEST(Rule2Framing, BackToBackFrames) {
    Bench::check_back_to_back({{64, 48, kDisparities, true},
                               {64, 48, kDisparities, true},
                               {37, 23, kDisparities, true},
                               {64, 48, kDisparities, false},
                               {13, 9, kDisparities, true},
                               {40, 30, kDisparities, true}},
                              Input::kStructured);
}

TEST(Rule2Sizes, WidthOne) {
    Bench::check_width_one(Input::kStructured);
}

}  // namespace
}  // namespace stereo::tb
