// stereo_ca_rule2 against stereo::ca_rule2: every value of every pixel and disparity, for the
// rule-1 output of a random pair (what rule 2 sees in the pipeline), smooth random planes on
// which the count of agreeing neighbours straddles the threshold of 7, small values (the strict
// 2|n - c| < c boundary), values near the maximum (the widest product), CA off (identity), odd
// and tiny frames (borders, zero padding never agrees), random clock enables, frames back to back.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <ostream>
#include <random>
#include <string>

#include "stage_driver.hpp"  // first: it includes the Verilator runtime headers quietly

#include "Vstereo_ca_rule2.h"
#include "stereo/pipeline.hpp"
#include "tb_options.hpp"

namespace stereo::tb {
namespace {

constexpr int kDisparities = 16;  // NDISP of Vstereo_ca_rule2
constexpr int kBits = fx::kAggBits;

struct Rule2Stage {
    using Model = Vstereo_ca_rule2;
    static constexpr const char* kName = "stereo_ca_rule2";
    static void scramble(Model& model, std::mt19937& rng) {
        randomize_bits(model.in_data, kDisparities * kBits, rng);
    }
    static std::vector<std::uint32_t> outputs(const Model& model) {
        return port_words(model.out_data);
    }
};

using Rule2Driver = StageDriver<Rule2Stage>;

Dsi run_rule2(Rule2Driver& driver, const Dsi& input, bool use_ca) {
    auto& model = driver.model();
    model.cfg_width = static_cast<std::uint16_t>(input.width());
    model.cfg_height = static_cast<std::uint16_t>(input.height());
    model.cfg_use_ca = use_ca ? 1 : 0;
    Dsi rtl(input.width(), input.height(), kDisparities);
    driver.run_frame(
        input.width(), input.height(),
        [&](Vstereo_ca_rule2& m, int x, int y) { put_column(m.in_data, input, x, y, kBits); },
        [&](const Vstereo_ca_rule2& m, int x, int y) { get_column(m.out_data, rtl, x, y, kBits); });
    return rtl;
}

Dsi expected_rule2(const Dsi& input, bool use_ca) {
    return use_ca ? ca_rule2(input) : input;
}

// ---- Inputs ----------------------------------------------------------------------------------

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

enum class Input { kPairRule1, kSmooth, kSmallValues, kNearMaximum, kFull14Bits };

const char* input_name(Input input) {
    switch (input) {
        case Input::kPairRule1:
            return "pair";
        case Input::kSmooth:
            return "smooth";
        case Input::kSmallValues:
            return "small";
        case Input::kNearMaximum:
            return "nearmax";
        case Input::kFull14Bits:
            return "full14bits";
    }
    return "?";
}

Dsi make_input(Input input, int width, int height, std::mt19937& rng) {
    switch (input) {
        case Input::kPairRule1:
            return pair_rule1(width, height, rng);
        case Input::kSmooth:
            return smooth_volume(width, height, rng);
        case Input::kSmallValues:  // 1..5: agreement decided at 2|n - c| == c, count near 7
            return uniform_volume(width, height, kDisparities, 1, 5, rng);
        case Input::kNearMaximum:  // fires everywhere inside: the product at its widest
            return uniform_volume(width, height, kDisparities, fx::kAggMax - 300, fx::kAggMax, rng);
        case Input::kFull14Bits:  // for the identity only: every bit must pass
            return uniform_volume(width, height, kDisparities, 0, (1 << kBits) - 1, rng);
    }
    return {};
}

struct RuleCase {
    int width, height;
    Input input;
    bool use_ca;
    double ce_low;
};

// Test names, and the parameter as ctest and GoogleTest print it.
std::string describe(const RuleCase& c) {
    return std::to_string(c.width) + "x" + std::to_string(c.height) + "_" + input_name(c.input) +
           (c.use_ca ? "_ca" : "_noca") + "_celow" +
           std::to_string(static_cast<int>(c.ce_low * 100));
}

void PrintTo(const RuleCase& c, std::ostream* os) {
    *os << describe(c);
}

std::string case_name(const ::testing::TestParamInfo<RuleCase>& info) {
    return describe(info.param);
}

class Volumes : public ::testing::TestWithParam<RuleCase> {};

TEST_P(Volumes, EveryValueEqualsTheModel) {
    const RuleCase c = GetParam();
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    Rule2Driver driver(seed, c.ce_low);
    for (int frame = 0; frame < kFramesPerCase; ++frame) {
        const Dsi input = make_input(c.input, c.width, c.height, rng);
        const Dsi expected = expected_rule2(input, c.use_ca);
        if (c.use_ca && frame == 0) {
            std::cout << "[fires] rule 2 changes " << 100.0 * changed_fraction(input, expected)
                      << " % of the cells\n";
        }
        EXPECT_TRUE(same_volume(expected, run_rule2(driver, input, c.use_ca), kDisparities))
            << "frame " << frame;
    }
}

INSTANTIATE_TEST_SUITE_P(Rule2, Volumes,
                         ::testing::Values(RuleCase{64, 48, Input::kPairRule1, true, 0.0},
                                           RuleCase{64, 48, Input::kSmooth, true, 0.3},
                                           RuleCase{64, 48, Input::kSmallValues, true, 0.2},
                                           RuleCase{64, 48, Input::kNearMaximum, true, 0.2},
                                           RuleCase{37, 23, Input::kSmooth, true, 0.25},
                                           RuleCase{37, 23, Input::kPairRule1, true, 0.1},
                                           RuleCase{13, 9, Input::kSmooth, true, 0.5},
                                           RuleCase{13, 9, Input::kSmallValues, true, 0.3},
                                           RuleCase{3, 3, Input::kNearMaximum, true, 0.3},
                                           RuleCase{3, 3, Input::kSmooth, true, 0.0},
                                           // CA off: the identity, on every bit of the 14
                                           RuleCase{64, 48, Input::kFull14Bits, false, 0.3},
                                           RuleCase{13, 9, Input::kSmooth, false, 0.2},
                                           RuleCase{3, 3, Input::kFull14Bits, false, 0.2}),
                         case_name);

// The smooth inputs must make the test strong: the rule has to fire on many cells, not all.
TEST(Rule2Inputs, SmoothVolumesMakeTheRuleFireOnPartOfTheCells) {
    std::mt19937 rng(test_seed());
    const Dsi input = smooth_volume(64, 48, rng);
    const double fired = changed_fraction(input, ca_rule2(input));
    EXPECT_GT(fired, 0.15);
    EXPECT_LT(fired, 0.85);
}

// Frames follow each other without idle steps, changing size and CA: the line buffer
// and the column registers hold the previous frame and its flush garbage.
TEST(Rule2Framing, BackToBackFrames) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    Rule2Driver driver(seed, 0.1);
    struct Frame {
        int width, height;
        bool use_ca;
    };
    int previous_height = 0;
    for (const Frame f : {Frame{64, 48, true}, Frame{64, 48, true}, Frame{37, 23, true},
                          Frame{64, 48, false}, Frame{13, 9, true}, Frame{40, 30, true}}) {
        // The contract of every stage (docs/rtl.md): a frame taller than the one before needs
        // the coordinate registers cleared between them, since the flush filler still in flight
        // (rows >= the old height) lies inside the new frame; stereo_top clears them when a
        // frame's last output leaves. Same-size and shorter frames follow without a reset.
        if (f.height > previous_height) {
            driver.reset();
        }
        previous_height = f.height;
        const Dsi input = smooth_volume(f.width, f.height, rng);
        EXPECT_TRUE(same_volume(expected_rule2(input, f.use_ca), run_rule2(driver, input, f.use_ca),
                                kDisparities))
            << f.width << "x" << f.height << " CA " << f.use_ca;
    }
}

// Width 1: the line buffer's read-ahead address is the word being written, which it passes
// straight through (a read-first RAM alone would deliver every row one row late).
TEST(Rule2Sizes, WidthOne) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    Rule2Driver driver(seed, 0.0);
    const Dsi input = smooth_volume(1, 7, rng);
    EXPECT_TRUE(same_volume(ca_rule2(input), run_rule2(driver, input, true), kDisparities));
}

}  // namespace
}  // namespace stereo::tb
