// stereo_ca_plane as CA rule 1 (Vstereo_ca_rule1) against stereo::ca_rule1 and as CA rule 2
// (Vstereo_ca_rule2) against stereo::ca_rule2: every value of every pixel and disparity, for what
// the rule sees in the pipeline (the aggregate of a random pair with a true disparity, for rule 2
// with rule 1 applied), structured volumes on which the rule fires often (rule 1: clustered
// values along d; rule 2: smooth planes whose count of agreeing neighbours straddles the
// threshold of 7), small values (the strict 2|n - c| < c boundary), values near the maximum (the
// widest sum and product), cfg_ndisp < NDISP (rule 1: plane cfg_ndisp must not count as a
// neighbour; rule 2 ignores it), CA off (identity), odd and tiny frames (borders, zero padding
// never agrees), random clock enables, frames back to back and width one.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "ca_rule_bench.hpp"  // first: it includes the Verilator runtime headers quietly

#include "Vstereo_ca_rule1.h"
#include "Vstereo_ca_rule2.h"
#include "stereo/pipeline.hpp"

namespace stereo::tb {
namespace {

constexpr int kDisparities = table::verilated("Vstereo_ca_rule1").params.ndisp;
static_assert(kDisparities == table::verilated("Vstereo_ca_rule2").params.ndisp);

// The aggregate of a random pair with true disparity 3: what rule 1 sees in the pipeline.
Dsi pair_aggregate(int width, int height, std::mt19937& rng) {
    return aggregate(pair_cost(width, height, kDisparities, 3, rng),
                     gaussian_kernel(5, fx::kDefaultSigma));
}

// `base` plus uniform noise over a range `spread` wide, inside the aggregate's range.
Dsi::Value noisy(int base, double spread, std::mt19937& rng) {
    std::uniform_real_distribution<double> unit(-0.5, 0.5);
    const int value = base + static_cast<int>(spread * unit(rng));
    return static_cast<Dsi::Value>(std::clamp(value, 0, fx::kAggMax));
}

// Per pixel a base value and a spread, per disparity the base plus noise within the spread:
// neighbouring d agree (2|n - c| < c) where the spread is small, which makes rule 1 fire often,
// and disagree where it is large.
Dsi clustered_volume(int width, int height, std::mt19937& rng) {
    Dsi volume(width, height, kDisparities);
    std::uniform_int_distribution<int> base_value(0, fx::kAggMax);
    std::uniform_real_distribution<double> spread_fraction(0.0, 3.0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const int base = base_value(rng);
            const double spread = base * spread_fraction(rng);
            for (int d = 0; d < kDisparities; ++d) {
                volume.at(x, y, d) = noisy(base, spread, rng);
            }
        }
    }
    return volume;
}

// Every plane a base value with per-pixel noise whose amplitude changes from plane to plane and
// across the image: where it is small nearly all 8 neighbours agree and rule 2 fires, where it
// is large the count falls below 7; in between it straddles the threshold.
Dsi smooth_volume(int width, int height, std::mt19937& rng) {
    Dsi volume(width, height, kDisparities);
    std::uniform_int_distribution<int> base_value(200, fx::kAggMax);
    std::uniform_real_distribution<double> amplitude(0.3, 1.4);
    for (int d = 0; d < kDisparities; ++d) {
        const int base = base_value(rng);
        const double left_amplitude = amplitude(rng);
        const double right_amplitude = amplitude(rng);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                // The amplitude ramps across the row, so a plane holds several regimes.
                const double t = width > 1 ? static_cast<double>(x) / (width - 1) : 0.0;
                const double spread = base * ((1 - t) * left_amplitude + t * right_amplitude);
                volume.at(x, y, d) = noisy(base, spread, rng);
            }
        }
    }
    return volume;
}

struct Rule1 {
    using Model = Vstereo_ca_rule1;
    static constexpr const char* kPrefix = "Vstereo_ca_rule1";
    static constexpr const char* kName = "ca_rule1";
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

struct Rule2 {
    using Model = Vstereo_ca_rule2;
    static constexpr const char* kPrefix = "Vstereo_ca_rule2";
    static constexpr const char* kName = "ca_rule2";
    static constexpr int kSmallLow = 1;  // 1..5: agreement decided at 2|n - c| == c, count near 7
    static constexpr int kSmallHigh = 5;
    static Dsi apply(const Dsi& volume) { return ca_rule2(volume); }
    static Dsi pair(int width, int height, std::mt19937& rng) {
        return ca_rule1(pair_aggregate(width, height, rng));
    }
    static Dsi structured(int width, int height, std::mt19937& rng) {
        return smooth_volume(width, height, rng);
    }
};

using Input = CaInput;
using tb::PrintTo;  // by describe()

// The cases of both rules: every input at 64x48 down to 3x3, CA off on every bit of the 14.
std::vector<CaCase> cases_of_both_rules() {
    const int n = kDisparities;
    return {
        CaCase{64, 48, Input::kPair, n, true, 0.0},
        CaCase{64, 48, Input::kStructured, n, true, 0.3},
        CaCase{64, 48, Input::kSmallValues, n, true, 0.2},
        CaCase{64, 48, Input::kNearMaximum, n, true, 0.2},
        CaCase{37, 23, Input::kStructured, n, true, 0.25},
        CaCase{37, 23, Input::kPair, n, true, 0.1},
        CaCase{13, 9, Input::kStructured, n, true, 0.5},
        CaCase{13, 9, Input::kSmallValues, n, true, 0.3},
        CaCase{3, 3, Input::kStructured, n, true, 0.3},
        CaCase{3, 3, Input::kSmallValues, n, true, 0.0},
        CaCase{3, 3, Input::kNearMaximum, n, true, 0.3},
        CaCase{64, 48, Input::kFull14Bits, n, false, 0.3},
        CaCase{13, 9, Input::kStructured, n, false, 0.2},
        CaCase{3, 3, Input::kFull14Bits, n, false, 0.2},
    };
}

// cfg_ndisp < NDISP: for rule 1 the last used plane has no d+1 neighbour.
std::vector<CaCase> cases_of_rule1() {
    std::vector<CaCase> cases = cases_of_both_rules();
    cases.insert(cases.end(), {CaCase{64, 48, Input::kStructured, 9, true, 0.2},
                               CaCase{37, 23, Input::kStructured, 15, true, 0.2},
                               CaCase{13, 9, Input::kSmallValues, 2, true, 0.2},
                               CaCase{13, 9, Input::kStructured, 1, true, 0.2},
                               CaCase{64, 48, Input::kPair, 5, true, 0.1},
                               CaCase{13, 9, Input::kStructured, 7, false, 0.2}});
    return cases;
}

// Frames back to back, changing size, cfg_ndisp and CA.
const std::vector<CaFrame> kBackToBack = {{64, 48, 16, true}, {64, 48, 16, true},
                                          {37, 23, 9, true},  {64, 48, 16, false},
                                          {13, 9, 16, true},  {40, 30, 12, true}};

template <typename Rule>
class Volumes : public ::testing::TestWithParam<CaCase> {
  protected:
    static void check() { CaRuleBench<Rule>::check_case(GetParam()); }
};
using Rule1Volumes = Volumes<Rule1>;
using Rule2Volumes = Volumes<Rule2>;

TEST_P(Rule1Volumes, EveryValueEqualsTheModel) {
    check();
}
TEST_P(Rule2Volumes, EveryValueEqualsTheModel) {
    check();
}
INSTANTIATE_TEST_SUITE_P(Ca, Rule1Volumes, ::testing::ValuesIn(cases_of_rule1()),
                         case_name<CaCase>);
INSTANTIATE_TEST_SUITE_P(Ca, Rule2Volumes, ::testing::ValuesIn(cases_of_both_rules()),
                         case_name<CaCase>);

// The structured inputs must make the tests strong: rule 1 has to fire on many cells, rule 2 on
// many but not all.
TEST(Inputs, ClusteredVolumesMakeRule1FireOften) {
    std::mt19937 rng(test_seed());
    const Dsi input = clustered_volume(64, 48, rng);
    EXPECT_GT(changed_fraction(input, ca_rule1(input)), 0.3);
}

TEST(Inputs, SmoothVolumesMakeRule2FireOnPartOfTheCells) {
    std::mt19937 rng(test_seed());
    const Dsi input = smooth_volume(64, 48, rng);
    const double fired = changed_fraction(input, ca_rule2(input));
    EXPECT_GT(fired, 0.15);
    EXPECT_LT(fired, 0.85);
}

TEST(Framing, BackToBackFrames) {
    CaRuleBench<Rule1>::check_back_to_back(kBackToBack, Input::kStructured);
    CaRuleBench<Rule2>::check_back_to_back(kBackToBack, Input::kStructured);
}

TEST(Sizes, WidthOne) {
    CaRuleBench<Rule1>::check_width_one(Input::kStructured);
    CaRuleBench<Rule2>::check_width_one(Input::kStructured);
}

}  // namespace
}  // namespace stereo::tb
