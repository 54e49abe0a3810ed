// stereo_ca_rule1 against stereo::ca_rule1: every value of every pixel and disparity, for the
// aggregate of a random pair with a true disparity, clustered random volumes on which the rule
// fires often, small values (the strict 2|n - c| < c boundary), values near the maximum (the
// widest 3x3 sum), cfg_ndisp < NDISP (plane cfg_ndisp must not count as a neighbour), CA off
// (identity), odd and tiny frames, random clock enables, and frames back to back.
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <ostream>
#include <random>
#include <string>

#include "stage_driver.hpp"  // first: it includes the Verilator runtime headers quietly

#include "Vstereo_ca_rule1.h"
#include "stereo/pipeline.hpp"
#include "tb_options.hpp"

namespace stereo::tb {
namespace {

constexpr int kDisparities = 16;  // NDISP of Vstereo_ca_rule1
constexpr int kBits = fx::kAggBits;

struct Rule1Stage {
    using Model = Vstereo_ca_rule1;
    static constexpr const char* kName = "stereo_ca_rule1";
    static void scramble(Model& model, std::mt19937& rng) {
        randomize_bits(model.in_data, kDisparities * kBits, rng);
    }
    static std::vector<std::uint32_t> outputs(const Model& model) {
        return port_words(model.out_data);
    }
};

using Rule1Driver = StageDriver<Rule1Stage>;

// Runs one frame of the NDISP-plane `input`; returns all NDISP output planes.
Dsi run_rule1(Rule1Driver& driver, const Dsi& input, int ndisp, bool use_ca) {
    auto& model = driver.model();
    model.cfg_width = static_cast<std::uint16_t>(input.width());
    model.cfg_height = static_cast<std::uint16_t>(input.height());
    model.cfg_ndisp = static_cast<std::uint16_t>(ndisp);
    model.cfg_use_ca = use_ca ? 1 : 0;
    Dsi rtl(input.width(), input.height(), kDisparities);
    driver.run_frame(
        input.width(), input.height(),
        [&](Vstereo_ca_rule1& m, int x, int y) { put_column(m.in_data, input, x, y, kBits); },
        [&](const Vstereo_ca_rule1& m, int x, int y) { get_column(m.out_data, rtl, x, y, kBits); });
    return rtl;
}

// The model sees only the cfg_ndisp planes the core uses; with CA off the stage is the identity.
Dsi expected_rule1(const Dsi& input, int ndisp, bool use_ca) {
    const Dsi used = truncated(input, ndisp);
    return use_ca ? ca_rule1(used) : used;
}

// ---- Inputs ----------------------------------------------------------------------------------

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

enum class Input { kPairAggregate, kClustered, kSmallValues, kNearMaximum, kFull14Bits };

const char* input_name(Input input) {
    switch (input) {
        case Input::kPairAggregate:
            return "pair";
        case Input::kClustered:
            return "clustered";
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
        case Input::kPairAggregate:
            return pair_aggregate(width, height, rng);
        case Input::kClustered:
            return clustered_volume(width, height, rng);
        case Input::kSmallValues:  // 0..6 holds every case of 2|n - c| < c versus == c
            return uniform_volume(width, height, kDisparities, 0, 6, rng);
        case Input::kNearMaximum:  // 3x3 sums up to 9 * 12240, the widest product
            return uniform_volume(width, height, kDisparities, fx::kAggMax - 300, fx::kAggMax, rng);
        case Input::kFull14Bits:  // for the identity only: every bit must pass
            return uniform_volume(width, height, kDisparities, 0, (1 << kBits) - 1, rng);
    }
    return {};
}

struct RuleCase {
    int width, height;
    Input input;
    int ndisp;
    bool use_ca;
    double ce_low;
};

// Test names, and the parameter as ctest and GoogleTest print it.
std::string describe(const RuleCase& c) {
    return std::to_string(c.width) + "x" + std::to_string(c.height) + "_" + input_name(c.input) +
           "_ndisp" + std::to_string(c.ndisp) + (c.use_ca ? "_ca" : "_noca") + "_celow" +
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
    Rule1Driver driver(seed, c.ce_low);
    for (int frame = 0; frame < kFramesPerCase; ++frame) {
        const Dsi input = make_input(c.input, c.width, c.height, rng);
        const Dsi expected = expected_rule1(input, c.ndisp, c.use_ca);
        if (c.use_ca && frame == 0) {
            std::cout << "[fires] rule 1 changes "
                      << 100.0 * changed_fraction(truncated(input, c.ndisp), expected)
                      << " % of the cells\n";
        }
        EXPECT_TRUE(same_volume(expected, run_rule1(driver, input, c.ndisp, c.use_ca), c.ndisp))
            << "frame " << frame;
    }
}

INSTANTIATE_TEST_SUITE_P(
    Rule1, Volumes,
    ::testing::Values(RuleCase{64, 48, Input::kPairAggregate, 16, true, 0.0},
                      RuleCase{64, 48, Input::kClustered, 16, true, 0.3},
                      RuleCase{64, 48, Input::kSmallValues, 16, true, 0.2},
                      RuleCase{64, 48, Input::kNearMaximum, 16, true, 0.2},
                      RuleCase{37, 23, Input::kClustered, 16, true, 0.25},
                      RuleCase{37, 23, Input::kPairAggregate, 16, true, 0.1},
                      RuleCase{13, 9, Input::kClustered, 16, true, 0.5},
                      RuleCase{13, 9, Input::kSmallValues, 16, true, 0.3},
                      RuleCase{3, 3, Input::kClustered, 16, true, 0.3},
                      RuleCase{3, 3, Input::kSmallValues, 16, true, 0.0},
                      // cfg_ndisp < NDISP: the last used plane has no d+1 neighbour
                      RuleCase{64, 48, Input::kClustered, 9, true, 0.2},
                      RuleCase{37, 23, Input::kClustered, 15, true, 0.2},
                      RuleCase{13, 9, Input::kSmallValues, 2, true, 0.2},
                      RuleCase{13, 9, Input::kClustered, 1, true, 0.2},
                      RuleCase{64, 48, Input::kPairAggregate, 5, true, 0.1},
                      // CA off: the identity, on every bit of the 14
                      RuleCase{64, 48, Input::kFull14Bits, 16, false, 0.3},
                      RuleCase{13, 9, Input::kClustered, 7, false, 0.2},
                      RuleCase{3, 3, Input::kFull14Bits, 16, false, 0.2}),
    case_name);

// The clustered inputs must make the test strong: the rule has to fire on many cells.
TEST(Rule1Inputs, ClusteredVolumesMakeTheRuleFireOften) {
    std::mt19937 rng(test_seed());
    const Dsi input = clustered_volume(64, 48, rng);
    EXPECT_GT(changed_fraction(input, ca_rule1(input)), 0.3);
}

// Frames follow each other without idle steps, changing size, cfg_ndisp and CA: the line
// buffer and the column registers hold the previous frame and its flush garbage.
TEST(Rule1Framing, BackToBackFrames) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    Rule1Driver driver(seed, 0.1);
    struct Frame {
        int width, height, ndisp;
        bool use_ca;
    };
    int previous_height = 0;
    for (const Frame f :
         {Frame{64, 48, 16, true}, Frame{64, 48, 16, true}, Frame{37, 23, 9, true},
          Frame{64, 48, 16, false}, Frame{13, 9, 16, true}, Frame{40, 30, 12, true}}) {
        // The contract of every stage (docs/rtl.md): a frame taller than the one before needs
        // the coordinate registers cleared between them, since the flush filler still in flight
        // (rows >= the old height) lies inside the new frame; stereo_top clears them when a
        // frame's last output leaves. Same-size and shorter frames follow without a reset.
        if (f.height > previous_height) {
            driver.reset();
        }
        previous_height = f.height;
        const Dsi input = clustered_volume(f.width, f.height, rng);
        EXPECT_TRUE(same_volume(expected_rule1(input, f.ndisp, f.use_ca),
                                run_rule1(driver, input, f.ndisp, f.use_ca), f.ndisp))
            << f.width << "x" << f.height << " ndisp " << f.ndisp << " CA " << f.use_ca;
    }
}

// Width 1: the line buffer's read-ahead address is the word being written, which it passes
// straight through (a read-first RAM alone would deliver every row one row late).
TEST(Rule1Sizes, WidthOne) {
    const std::uint32_t seed = test_seed();
    std::mt19937 rng(seed);
    Rule1Driver driver(seed, 0.0);
    const Dsi input = clustered_volume(1, 7, rng);
    EXPECT_TRUE(
        same_volume(ca_rule1(input), run_rule1(driver, input, kDisparities, true), kDisparities));
}

}  // namespace
}  // namespace stereo::tb
