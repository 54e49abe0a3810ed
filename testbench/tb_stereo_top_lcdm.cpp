// stereo_top with the LCDM cost stage (COST = 1, Verilated as Vstereo_top_lcdm) against
// stereo::match with the "lcdm" cost, pixel for pixel through its AXI4-Stream ports: random
// colour pairs with input gaps and output stalls, a relit pair, a real crop, frames back to back
// and a reset in the middle of a frame. Built once per LCDM configuration (STEREO_TB_LCDM_CONFIG
// names it, testbench/CMakeLists.txt): small-lcdm and lcdm-lanes4 (LANES < NDISP).
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "stereo/pipeline.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/test_support.hpp"
#include "stereo_top_sim.hpp"
#include "tb_compare.hpp"
#include "tb_cosim.hpp"
#include "tb_options.hpp"
#include "tb_real_pairs.hpp"

namespace stereo::sim {
namespace {

using tb::same_map;

#ifndef STEREO_TB_LCDM_CONFIG
#define STEREO_TB_LCDM_CONFIG "small-lcdm"
#endif

MatchParams lcdm_params(int ndisp, int window, bool use_ca) {
    MatchParams params{ndisp, window, fx::kDefaultSigma, use_ca};
    params.cost = "lcdm";
    return params;
}

// The LCDM configuration, frame by frame (tb_cosim.hpp); run() as an 8-bit map.
class LcdmCosim : public tb::Cosim {
  public:
    LcdmCosim() : tb::Cosim(top_config_named(STEREO_TB_LCDM_CONFIG)) {}
    ValidatedDisparity run_validated(const Image& left, const Image& right,
                                     const MatchParams& params, const Traffic& traffic) {
        return tb::Cosim::run(left, right, params, traffic);
    }
    DisparityMap run(const Image& left, const Image& right, const MatchParams& params,
                     const Traffic& traffic) {
        return to_label_map(run_validated(left, right, params, traffic));
    }
};

using tb::RandomCase;

class LcdmRandomPairs : public tb::RandomPairTest {};

TEST_P(LcdmRandomPairs, EveryPixelEqualsTheModel) {
    const MatchParams params = lcdm_params(c.ndisp, c.window, c.use_ca);
    LcdmCosim cosim;
    EXPECT_TRUE(same_map(match(pair.left, pair.right, params),
                         cosim.run(pair.left, pair.right, params, traffic)));
}

INSTANTIATE_TEST_SUITE_P(Lcdm, LcdmRandomPairs,
                         ::testing::Values(RandomCase{64, 48, 16, 5, true, 0.0, 0.0},
                                           RandomCase{64, 48, 16, 5, true, 0.3, 0.3},
                                           RandomCase{64, 48, 16, 5, false, 0.2, 0.5},
                                           RandomCase{37, 23, 9, 3, true, 0.1, 0.1},
                                           RandomCase{23, 17, 4, 1, false, 0.0, 0.3}));

TEST(LcdmRealPair, TsukubaCropWithTheRightImageDarkened) {
    const auto pair = tb::tsukuba_crop();
    if (!pair) {
        GTEST_SKIP() << "tsukuba not found in " << io::data_dir();
    }
    Image darker = pair->right;
    for (auto& p : darker.pixels) {
        p = static_cast<std::uint8_t>(p * 3 / 4);
    }
    const MatchParams params = lcdm_params(16, 5, true);
    const std::uint32_t seed = tb::test_seed();
    LcdmCosim cosim;
    EXPECT_TRUE(same_map(match(pair->left, pair->right, params),
                         cosim.run(pair->left, pair->right, params, {0.2, 0.2, seed})));
    EXPECT_TRUE(same_map(match(pair->left, darker, params),
                         cosim.run(pair->left, darker, params, {0.2, 0.2, seed})));
}

// Stage 6 behind the LCDM cost: signed ranges (the LCDM points wait in the cost stage's left
// delay line), uniqueness, left-right and sub-pixel output, all three output fields compared.
TEST(LcdmStage6, SignedRangesWithValidation) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    const auto [left, right] = test::shifted_pair(64, 48, 3, -2, 20, rng);
    LcdmCosim cosim;
    for (const int min_disp : {-8, -4, 0, 3}) {
        MatchParams params = lcdm_params(16, 5, true);
        params.min_disp = min_disp;
        params.validation = ValidationParams::all_on();
        EXPECT_TRUE(tb::same_validated(match_validated(left, right, params),
                                       cosim.run_validated(left, right, params, {0.2, 0.2, seed})))
            << "min_disp " << min_disp;
    }
}

TEST(LcdmFraming, BackToBackFramesAndAResetInTheMiddleOfAFrame) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    const MatchParams params = lcdm_params(16, 5, true);
    LcdmCosim cosim;
    for (const auto& [width, height] : {std::pair{64, 48}, std::pair{37, 23}, std::pair{64, 48}}) {
        const auto [left, right] = test::shifted_pair(width, height, 3, 4, 10, rng);
        EXPECT_TRUE(
            same_map(match(left, right, params), cosim.run(left, right, params, {0.1, 0.1, seed})))
            << width << "x" << height;
    }
    const auto [left, right] = test::shifted_pair(64, 48, 3, 5, 15, rng);
    cosim.reset_mid_frame(left, right, params, 64 * 48 / 2, 100, {0.2, 0.2, seed});
    const auto [left2, right2] = test::shifted_pair(64, 48, 3, 7, 15, rng);
    EXPECT_TRUE(
        same_map(match(left2, right2, params), cosim.run(left2, right2, params, {0.2, 0.2, seed})));
}

}  // namespace
}  // namespace stereo::sim
