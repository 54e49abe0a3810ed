// stereo_top with another cost stage than AD against stereo::match with that cost, pixel for
// pixel through its AXI4-Stream ports: random colour pairs with input gaps and output stalls, a
// relit pair, a real crop, signed ranges with stage 6, frames back to back of different sizes, a
// reset in the middle of a frame, and the frame's cycle count. Built once per configuration
// (STEREO_TB_COST_CONFIG names it, testbench/CMakeLists.txt): small-lcdm and lcdm-lanes4 (the
// LCDM cost, COST = 1), small-census and census-lanes4 (the census stage, COST = 2), and
// census-recompute and census-recompute-lanes4 (the census core in the lean memory architecture,
// RECOMPUTE_COSTS = 1); LANES < NDISP in the -lanes4 ones.
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

// STEREO_TB_COST_CONFIG: the configuration's name, set by testbench/CMakeLists.txt for each target.
const TopConfig& config() {
    return top_config_named(STEREO_TB_COST_CONFIG);
}

MatchParams cost_params(int ndisp, int window, bool use_ca) {
    MatchParams params{ndisp, window, fx::kDefaultSigma, use_ca};
    params.cost = tb::model_cost_name(config().cost);
    return params;
}

// The configuration, frame by frame (tb_cosim.hpp); run() as an 8-bit map.
class CostCosim : public tb::Cosim {
  public:
    CostCosim() : tb::Cosim(config()) {}
    ValidatedDisparity run_validated(const Image& left, const Image& right,
                                     const MatchParams& params, const Traffic& traffic,
                                     StreamResult* result = nullptr) {
        return tb::Cosim::run(left, right, params, traffic, result);
    }
    DisparityMap run(const Image& left, const Image& right, const MatchParams& params,
                     const Traffic& traffic) {
        return to_label_map(run_validated(left, right, params, traffic));
    }
};

using tb::RandomCase;

class CostRandomPairs : public tb::RandomPairTest {};

TEST_P(CostRandomPairs, EveryPixelEqualsTheModel) {
    const MatchParams params = cost_params(c.ndisp, c.window, c.use_ca);
    CostCosim cosim;
    EXPECT_TRUE(same_map(match(pair.left, pair.right, params),
                         cosim.run(pair.left, pair.right, params, traffic)));
}

INSTANTIATE_TEST_SUITE_P(Cost, CostRandomPairs,
                         ::testing::Values(RandomCase{64, 48, 16, 5, true, 0.0, 0.0},
                                           RandomCase{64, 48, 16, 5, true, 0.3, 0.3},
                                           RandomCase{64, 48, 16, 5, false, 0.2, 0.5},
                                           RandomCase{37, 23, 9, 3, true, 0.1, 0.1},
                                           RandomCase{23, 17, 4, 1, false, 0.0, 0.3}));

TEST(CostRealPair, TsukubaCropWithTheRightImageDarkened) {
    const auto pair = tb::tsukuba_crop();
    if (!pair) {
        GTEST_SKIP() << "tsukuba not found in " << io::data_dir();
    }
    const Image darker = tb::darkened(pair->right);
    const MatchParams params = cost_params(16, 5, true);
    const std::uint32_t seed = tb::test_seed();
    CostCosim cosim;
    EXPECT_TRUE(same_map(match(pair->left, pair->right, params),
                         cosim.run(pair->left, pair->right, params, {0.2, 0.2, seed})));
    EXPECT_TRUE(same_map(match(pair->left, darker, params),
                         cosim.run(pair->left, darker, params, {0.2, 0.2, seed})));
}

// Stage 6 behind the cost: signed ranges (the LCDM points or census codes wait in the cost
// stage's left delay line), uniqueness, left-right and sub-pixel output, all three output fields
// compared.
TEST(CostStage6, SignedRangesWithValidation) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    const auto [left, right] = test::shifted_pair(64, 48, 3, -2, 20, rng);
    CostCosim cosim;
    for (const int min_disp : {-8, -4, 0, 3}) {
        MatchParams params = cost_params(16, 5, true);
        params.min_disp = min_disp;
        params.validation = ValidationParams::all_on();
        EXPECT_TRUE(tb::same_validated(match_validated(left, right, params),
                                       cosim.run_validated(left, right, params, {0.2, 0.2, seed})))
            << "min_disp " << min_disp;
    }
}

TEST(CostFraming, BackToBackFramesAndAResetInTheMiddleOfAFrame) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    const MatchParams params = cost_params(16, 5, true);
    CostCosim cosim;
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

// Frames of odd sizes, down to two pixels wide (the model's least: ndisp < width) or one high;
// the census window wraps over several rows of a narrow frame. Back to back, each compared.
TEST(CostFraming, NarrowAndFlatFrames) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    CostCosim cosim;
    for (const auto& [width, height] :
         {std::pair{2, 9}, std::pair{3, 7}, std::pair{5, 1}, std::pair{4, 3}, std::pair{17, 2}}) {
        const auto [left, right] = test::shifted_pair(width, height, 3, 1, 10, rng);
        const MatchParams params = cost_params(std::min(4, width - 1), 1, false);
        EXPECT_TRUE(
            same_map(match(left, right, params), cosim.run(left, right, params, {0.2, 0.2, seed})))
            << width << "x" << height;
    }
}

// Cycles of a frame without stalls: the stage table's formula for this cost (the census stage
// adds 2 W + 4 steps, stage_table.hpp kCensusStage), measured.
TEST(CostThroughput, FrameCyclesAreTheStageTables) {
    std::mt19937 rng(tb::test_seed());
    const TopConfig& point = config();
    for (const int min_disp : {0, -3}) {
        const auto [left, right] = test::shifted_pair(point.width, point.height, 3, 2, 10, rng);
        MatchParams params = cost_params(point.ndisp, point.window, true);
        params.min_disp = min_disp;
        CostCosim cosim;
        StreamResult result;
        EXPECT_TRUE(tb::same_validated(match_validated(left, right, params),
                                       cosim.run_validated(left, right, params, {}, &result)));
        EXPECT_EQ(result.cycles, static_cast<std::uint64_t>(table::frame_cycles(
                                     point.width, point.height, point.window, point.ndisp,
                                     point.lanes, min_disp, point.cost)))
            << "min_disp " << min_disp;
    }
}

}  // namespace
}  // namespace stereo::sim
