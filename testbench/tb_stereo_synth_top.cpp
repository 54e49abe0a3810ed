// stereo_synth_top, the FPGA build as it is synthesised (the constant default kernel, the radius
// WINDOW/2, MAX_MIN_DISP = 0), against the golden model: the HX8K's one-label 3x3 core
// ("ice40-ndisp1") and its 4-label 5x5 core at one label per clock ("ice40-ndisp4-lanes1"),
// docs/synthesis.md, and a census build (8 labels, 7x7, two per clock) whose aggregation keeps
// census codes in its line buffer ("fpga-census-ndisp8-lanes2"). Random pairs with and without
// the CA rules and stage 6, real crops, fewer labels than the build has, frames of two sizes back
// to back, input gaps and output stalls, and a minimum disparity outside the build's range
// (clamped to 0 and flagged).
#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "stereo/pipeline.hpp"
#include "stereo/stage_table.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/test_support.hpp"
#include "stereo_top_sim.hpp"
#include "tb_compare.hpp"
#include "tb_cosim.hpp"
#include "tb_options.hpp"

namespace stereo::sim {
namespace {

using tb::same_validated;

class FpgaTop : public ::testing::TestWithParam<std::string> {
  protected:
    const TopConfig& config() const { return top_config_named(GetParam()); }
    // The parameters the build can run: its window with the default kernel, its cost.
    MatchParams params(int ndisp, bool use_ca) const {
        MatchParams p{ndisp, config().window, fx::kDefaultSigma, use_ca};
        p.cost = tb::model_cost_name(config().cost);
        return p;
    }
};

TEST_P(FpgaTop, RandomPairsEqualTheModel) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    tb::Cosim cosim(config());
    for (const bool use_ca : {true, false}) {
        const Image left = test::random_image(config().width, config().height, 3, rng);
        const Image right = test::shifted_copy(left, config().ndisp / 2, 12, rng);
        const MatchParams p = params(config().ndisp, use_ca);
        EXPECT_TRUE(same_validated(match_validated(left, right, p),
                                   cosim.run(left, right, p, {0.2, 0.2, seed})))
            << "CA " << use_ca;
    }
}

TEST_P(FpgaTop, StageSixChecksAndFewerLabels) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    tb::Cosim cosim(config());
    for (int ndisp = config().ndisp; ndisp >= 1; ndisp -= 3) {
        const Image left = test::random_image(37, 23, 3, rng);
        const Image right = test::shifted_copy(left, 1, 20, rng);
        MatchParams p = params(ndisp, true);
        p.validation = {true, 15, true, 1, true};
        EXPECT_TRUE(same_validated(match_validated(left, right, p),
                                   cosim.run(left, right, p, {0.1, 0.3, seed})))
            << ndisp << " labels";
    }
}

TEST_P(FpgaTop, RealCropsEqualTheModel) {
    const std::filesystem::path left_path = io::aloe_dir() / "aloeL.jpg";
    const std::filesystem::path right_path = io::aloe_dir() / "aloeR.jpg";
    if (!std::filesystem::exists(left_path) || !std::filesystem::exists(right_path)) {
        GTEST_SKIP() << "the Aloe pair (opencv-doc) is not installed";
    }
    const io::ImagePair pair =
        io::crop(io::load_pair(left_path, right_path, 8), 50, 40, config().width, config().height);
    tb::Cosim cosim(config());
    MatchParams p = params(config().ndisp, true);
    p.validation = {true, 10, true, 1, true};
    EXPECT_TRUE(same_validated(match_validated(pair.left, pair.right, p),
                               cosim.run(pair.left, pair.right, p, {0.1, 0.1, tb::test_seed()})));
}

// Two frames of different sizes in one stream, without reset.
TEST_P(FpgaTop, BackToBackFramesOfTwoSizes) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    tb::Cosim cosim(config());
    for (const auto& [width, height] : {std::pair{config().width, config().height}, {19, 9}}) {
        const Image left = test::random_image(width, height, 3, rng);
        const Image right = test::shifted_copy(left, 1, 15, rng);
        const MatchParams p = params(config().ndisp, true);
        EXPECT_TRUE(same_validated(match_validated(left, right, p),
                                   cosim.run(left, right, p, {0.3, 0.1, seed})))
            << width << "x" << height;
    }
}

// MAX_MIN_DISP = 0: a minimum disparity is clamped to 0 and flags the configuration status bit.
TEST_P(FpgaTop, MinimumDisparityOutsideTheBuildIsClampedAndFlagged) {
    std::mt19937 rng(tb::test_seed());
    const Image left = test::random_image(config().width, config().height, 3, rng);
    const Image right = test::shifted_copy(left, 1, 10, rng);
    tb::Cosim cosim(config());
    MatchParams asked = params(config().ndisp, true);
    asked.min_disp = -2;
    cosim.sim().set_params({left.width, left.height, asked});
    const auto beats = frame_beats(left, right);
    const StreamResult result = cosim.sim().stream(beats, beats.size(), {}, 50 * beats.size());
    ASSERT_TRUE(result.completed);
    EXPECT_EQ(result.status, 1U << table::kStatusConfigClamped);
    EXPECT_TRUE(same_validated(match_validated(left, right, params(config().ndisp, true)),
                               assemble_validated(result.outputs, 0, left.width, left.height)));
}

// The build has one kernel: another window is refused, not silently mismatched.
TEST_P(FpgaTop, AnotherWindowIsRefused) {
    tb::Cosim cosim(config());
    MatchParams p = params(config().ndisp, true);
    p.window = config().window - 2;
    EXPECT_THROW(cosim.sim().set_params({16, 8, p}), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Ice40, FpgaTop,
                         ::testing::Values("ice40-ndisp1", "ice40-ndisp4-lanes1",
                                           "fpga-census-ndisp8-lanes2"),
                         [](const auto& info) {
                             std::string name = info.param;
                             for (char& c : name) {
                                 if (c == '-') {
                                     c = '_';
                                 }
                             }
                             return name;
                         });

}  // namespace
}  // namespace stereo::sim
