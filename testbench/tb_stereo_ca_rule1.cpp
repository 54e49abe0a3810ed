// stereo_ca_rule1 against stereo::ca_rule1: every value of every pixel and disparity, for the
// aggregate of a random pair with a true disparity, clustered random volumes on which the rule
// fires often, small values (the strict 2|n - c| < c boundary), values near the maximum (the
// widest 3x3 sum), cfg_ndisp < NDISP (plane cfg_ndisp must not count as a neighbour), CA off
// (identity), odd and tiny frames, random clock enables, and frames back to back.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "ca_rule_bench.hpp"  // first: it includes the Verilator runtime headers quietly

#include "Vstereo_ca_rule1.h"
#include "stereo/pipeline.hpp"

namespace stereo::tb {
namespace {

constexpr int kDisparities = table::verilated("Vstereo_ca_rule1").params.ndisp;

// The aggregate of a random pair with true disparity 3: what the rule sees in the pipeline.
Dsi pair_aggregate(int width, int height, std::mt19937& rng) {
    return aggregate(pair_cost(width, height, kDisparities, 3, rng),
                     gaussian_kernel(5, fx::kDefaultSigma));
}

// Per pixel a base value and a spread, per disparity the base plus noise within the spread:
// neighbouring d agree (2|n - c| < c) where the spread is small, which makes the rule fire often,
// and disagree where it is large.
Dsi clustered_volume(int width, int height, std::mt19937& rng) {
    Dsi volume(width, height, kDisparities);
    std::uniform_int_distribution<int> base_value(0, fx::kAggMax);
    std::uniform_real_distribution<double> spread_fraction(0.0, 3.0);
    std::uniform_real_distribution<double> unit(-0.5, 0.5);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const int base = base_value(rng);
            const double spread = base * spread_fraction(rng);
            for (int d = 0; d < kDisparities; ++d) {
                const int value = base + static_cast<int>(spread * unit(rng));
                volume.at(x, y, d) = static_cast<Dsi::Value>(std::clamp(value, 0, fx::kAggMax));
            }
        }
    }
    return volume;
}

struct Rule1 {
    using Model = Vstereo_ca_rule1;
    static constexpr const char* kPrefix = "Vstereo_ca_rule1";
    static constexpr const char* kName = "stereo_ca_rule1";
    static constexpr bool kHasNdisp = true;
    static constexpr const char* kStructuredName = "clustered";
    static constexpr int kSmallLow = 0;  // 0..6 holds every case of 2|n - c| < c versus == c
    static constexpr int kSmallHigh = 6;
    static Dsi apply(const Dsi& volume) { return ca_rule1(volume); }
    static Dsi pair(int width, int height, std::mt19937& rng) {
        return pair_aggregate(width, height, rng);
    }
    static Dsi structured(int width, int height, std::mt19937& rng) {
        return clustered_volume(width, height, rng);
    }
};

using Bench = CaRuleBench<Rule1>;
using Case = Bench::Case;
using Input = CaInput;

class Volumes : public ::testing::TestWithParam<Case> {};

TEST_P(Volumes, EveryValueEqualsTheModel) {
    Bench::check_case(GetParam());
}

INSTANTIATE_TEST_SUITE_P(
    Rule1, Volumes,
    ::testing::Values(
        Case{64, 48, Input::kPair, 16, true, 0.0}, Case{64, 48, Input::kStructured, 16, true, 0.3},
        Case{64, 48, Input::kSmallValues, 16, true, 0.2},
        Case{64, 48, Input::kNearMaximum, 16, true, 0.2},
        Case{37, 23, Input::kStructured, 16, true, 0.25}, Case{37, 23, Input::kPair, 16, true, 0.1},
        Case{13, 9, Input::kStructured, 16, true, 0.5},
        Case{13, 9, Input::kSmallValues, 16, true, 0.3},
        Case{3, 3, Input::kStructured, 16, true, 0.3},
        Case{3, 3, Input::kSmallValues, 16, true, 0.0},
        // cfg_ndisp < NDISP: the last used plane has no d+1 neighbour
        Case{64, 48, Input::kStructured, 9, true, 0.2},
        Case{37, 23, Input::kStructured, 15, true, 0.2},
        Case{13, 9, Input::kSmallValues, 2, true, 0.2},
        Case{13, 9, Input::kStructured, 1, true, 0.2}, Case{64, 48, Input::kPair, 5, true, 0.1},
        // CA off: the identity, on every bit of the 14
        Case{64, 48, Input::kFull14Bits, 16, false, 0.3},
        Case{13, 9, Input::kStructured, 7, false, 0.2},
        Case{3, 3, Input::kFull14Bits, 16, false, 0.2}),
    Bench::case_name);

// The clustered inputs must make the test strong: the rule has to fire on many cells.
TEST(Rule1Inputs, ClusteredVolumesMakeTheRuleFireOften) {
    std::mt19937 rng(test_seed());
    const Dsi input = clustered_volume(64, 48, rng);
    EXPECT_GT(changed_fraction(input, ca_rule1(input)), 0.3);
}

TEST(Rule1Framing, BackToBackFrames) {
    Bench::check_back_to_back({{64, 48, 16, true},
                               {64, 48, 16, true},
                               {37, 23, 9, true},
                               {64, 48, 16, false},
                               {13, 9, 16, true},
                               {40, 30, 12, true}},
                              Input::kStructured);
}

TEST(Rule1Sizes, WidthOne) {
    Bench::check_width_one(Input::kStructured);
}

}  // namespace
}  // namespace stereo::tb
