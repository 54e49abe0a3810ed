// stereo_top with adaptive support weights (ASW = 1, docs/asw.md) against the model's separable
// ASW, stereo::asw::match, pixel for pixel and field for field through its AXI4-Stream ports:
// random colour pairs with input gaps and output stalls, stage 6 over signed ranges, a real crop,
// a relit pair, frames back to back of different sizes, a reset in the middle of a frame, and
// the frame's cycle count. Built once per configuration (STEREO_TB_ASW_CONFIG names it,
// testbench/CMakeLists.txt): asw-census (diameter 5, every label per clock), asw-census-lanes4
// (4 per clock) and asw-ad-lanes4 (the truncated AD cost, diameter 31: the continuity factor of
// pass 2 weighs label jumps above 255 / 31, which 16 labels reach).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <utility>

#include "stereo/asw.hpp"
#include "stereo/stage_table.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/test_support.hpp"
#include "stereo_top_sim.hpp"
#include "tb_compare.hpp"
#include "tb_cosim.hpp"
#include "tb_options.hpp"
#include "tb_real_pairs.hpp"

namespace stereo::sim {
namespace {

using tb::same_validated;

// STEREO_TB_ASW_CONFIG: the configuration's name, set by testbench/CMakeLists.txt.
const TopConfig& config() {
    return top_config_named(STEREO_TB_ASW_CONFIG);
}

// The model's matcher that the core implements: the separable ASW of the core's diameter with
// the default responses, on the core's cost.
asw::Params asw_params() {
    asw::Params params;
    params.diameter = config().window;
    params.separable = true;
    params.threads = 1;
    return params;
}

MatchParams match_params(int ndisp, int min_disp, bool stage6) {
    MatchParams params{ndisp, config().window, fx::kDefaultSigma, false};
    params.cost = tb::model_cost_name(config().cost);
    params.min_disp = min_disp;
    if (stage6) {
        params.validation = ValidationParams::all_on();
    }
    return params;
}

ValidatedDisparity model(const Image& left, const Image& right, const MatchParams& params) {
    return asw::match(left, right, params, asw_params());
}

// The VGA build (-DSTEREO_COSIM_CONFIGS=full_asw, synthesis) is the model's hardware configuration.
static_assert(table::kFullAsw.window == asw::kHardwareDiameter &&
              table::kFullAsw.cost == table::kCostCensus);

TEST(AswConfiguration, IsAnAswBuild) {
    ASSERT_TRUE(config().asw);
    EXPECT_GE(config().window, table::kAswMinDiameter);
    EXPECT_LE(config().window, table::kAswMaxDiameter);
}

// The model's separable ASW equals the naive reference on a pair of this size: what the core is
// compared with is itself checked by an independent path.
TEST(AswReference, ModelEqualsNaiveAtTheCoresSize) {
    std::mt19937 rng(tb::test_seed());
    const auto [left, right] = test::shifted_pair(config().width, config().height, 3, 4, 25, rng);
    const MatchParams params = match_params(config().ndisp, -2, true);
    EXPECT_TRUE(same_validated(asw::match_naive(left, right, params, asw_params()),
                               model(left, right, params)));
}

struct AswCase {
    int width, height, ndisp, min_disp;
    bool stage6;
    double gap, stall;
};

void PrintTo(const AswCase& c, std::ostream* out) {
    *out << c.width << "x" << c.height << " ndisp " << c.ndisp << " min_disp " << c.min_disp
         << (c.stage6 ? " stage 6" : " plain") << " gap " << c.gap << " stall " << c.stall;
}

class AswRandomPairs : public ::testing::TestWithParam<AswCase> {};

TEST_P(AswRandomPairs, EveryPixelEqualsTheModel) {
    const AswCase c = GetParam();
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    const auto [left, right] = test::shifted_pair(c.width, c.height, 3, 3, 25, rng);
    const MatchParams params = match_params(c.ndisp, c.min_disp, c.stage6);
    tb::Cosim cosim(config());
    EXPECT_TRUE(same_validated(model(left, right, params),
                               cosim.run(left, right, params, {c.gap, c.stall, seed})));
}

INSTANTIATE_TEST_SUITE_P(Asw, AswRandomPairs,
                         ::testing::Values(AswCase{64, 48, 16, 0, false, 0.0, 0.0},
                                           AswCase{64, 48, 16, 0, true, 0.3, 0.3},
                                           AswCase{64, 48, 16, -5, true, 0.2, 0.5},
                                           AswCase{64, 48, 16, 4, true, 0.1, 0.1},
                                           AswCase{37, 33, 9, 0, true, 0.1, 0.2}));

// Two layers (disparities 2 and 14 in an 8x8 checkerboard of thirds): pass 1's labels jump by 12
// between them, which pass 2's continuity factor weighs where 12 > 255 / w (diameter 31; at 5 the
// factor is 255 for every jump below 51 labels). The test says whether it exercises the factor:
// the model without it must differ there.
TEST(AswContinuity, TwoLayersEqualTheModel) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    const auto [left, right] = test::shifted_pair(64, 48, 3, 2, 20, rng);
    Image layered = right;
    for (int y = 0; y < 48; ++y) {
        for (int x = 0; x < 64; ++x) {
            if ((x / 8 + y / 8) % 3 == 0) {
                for (int c = 0; c < 3; ++c) {
                    layered.pixels[(static_cast<std::size_t>(y) * 64 + x) * 3 + c] =
                        x + 14 < 64 ? left.at(x + 14, y, c)
                                    : static_cast<std::uint8_t>(rng() % 256);
                }
            }
        }
    }
    const MatchParams params = match_params(16, 0, true);
    tb::Cosim cosim(config());
    EXPECT_TRUE(same_validated(model(left, layered, params),
                               cosim.run(left, layered, params, {0.2, 0.2, seed})));
    if (255 / config().window < 12) {
        asw::Params no_continuity = asw_params();
        no_continuity.continuity = false;
        EXPECT_FALSE(tb::same_validated(model(left, layered, params),
                                        asw::match(left, layered, params, no_continuity)))
            << "the pair does not exercise the continuity factor";
    }
}

TEST(AswRealPair, TsukubaCropAndTheRightImageDarkened) {
    const auto pair = tb::tsukuba_crop();
    if (!pair) {
        GTEST_SKIP() << "tsukuba not found in " << io::data_dir();
    }
    const Image darker = tb::darkened(pair->right);
    const MatchParams params = match_params(16, 0, true);
    const std::uint32_t seed = tb::test_seed();
    tb::Cosim cosim(config());
    EXPECT_TRUE(same_validated(model(pair->left, pair->right, params),
                               cosim.run(pair->left, pair->right, params, {0.2, 0.2, seed})));
    EXPECT_TRUE(same_validated(model(pair->left, darker, params),
                               cosim.run(pair->left, darker, params, {0.2, 0.2, seed})));
}

TEST(AswFraming, BackToBackFramesAndAResetInTheMiddleOfAFrame) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    const MatchParams params = match_params(16, 0, true);
    tb::Cosim cosim(config());
    for (const auto& [width, height] : {std::pair{64, 48}, std::pair{37, 33}, std::pair{64, 48}}) {
        const auto [left, right] = test::shifted_pair(width, height, 3, 4, 10, rng);
        EXPECT_TRUE(same_validated(model(left, right, params),
                                   cosim.run(left, right, params, {0.1, 0.1, seed})))
            << width << "x" << height;
    }
    const auto [left, right] = test::shifted_pair(64, 48, 3, 5, 15, rng);
    cosim.reset_mid_frame(left, right, params, 64 * 48 / 2, 100, {0.2, 0.2, seed});
    const auto [left2, right2] = test::shifted_pair(64, 48, 3, 7, 15, rng);
    EXPECT_TRUE(same_validated(model(left2, right2, params),
                               cosim.run(left2, right2, params, {0.2, 0.2, seed})));
}

// Cycles of a frame without stalls: the stage table's formula (asw_frame_cycles), measured.
TEST(AswThroughput, FrameCyclesAreTheStageTables) {
    std::mt19937 rng(tb::test_seed());
    const TopConfig& point = config();
    for (const int min_disp : {0, -3}) {
        const auto [left, right] = test::shifted_pair(point.width, point.height, 3, 2, 10, rng);
        const MatchParams params = match_params(point.ndisp, min_disp, true);
        tb::Cosim cosim(point);
        StreamResult result;
        EXPECT_TRUE(same_validated(model(left, right, params),
                                   cosim.run(left, right, params, {}, &result)));
        EXPECT_EQ(result.cycles, static_cast<std::uint64_t>(table::asw_frame_cycles(
                                     point.width, point.height, point.window, point.ndisp,
                                     point.lanes, min_disp, point.cost)))
            << "min_disp " << min_disp;
    }
}

}  // namespace
}  // namespace stereo::sim
