// stereo_top against the golden model, pixel for pixel, through its AXI4-Stream ports, with
// random input gaps and output stalls, resets in the middle of a frame, back-to-back frames,
// real and synthetic images, and malformed streams. Built once per stereo_top configuration
// (STEREO_TB_TOP_CONFIG names it, testbench/CMakeLists.txt): the small one and the
// time-multiplexed lanes ones (LANES < NDISP), with the same checks; label counts above the
// configuration's NDISP are capped to it.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>

#include "stereo/pipeline.hpp"
#include "stereo/stage_table.hpp"
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

using tb::same_validated;

#ifndef STEREO_TB_TOP_CONFIG
#define STEREO_TB_TOP_CONFIG "small"
#endif

// The configuration under test.
const TopConfig& small() {
    return top_config_named(STEREO_TB_TOP_CONFIG);
}

// A label count of a test case, capped to the configuration's NDISP.
int labels(int ndisp) {
    return std::min(ndisp, small().ndisp);
}

// Cycles of one frame without stalls: the stage table's formula (stage_table.hpp, docs/rtl.md),
// G (W*H + (R + 2) * W + R + 11 + N + K) - 2 (G - 1) + 1, G = NDISP / LANES; the Throughput tests
// below measure it on the RTL.
std::uint64_t documented_cycles(int width, int height, int window, int min_disp) {
    return static_cast<std::uint64_t>(
        table::frame_cycles(width, height, window, small().ndisp, small().lanes, min_disp));
}

// The golden model's stage-6 output.
ValidatedDisparity expected(const Image& left, const Image& right, const MatchParams& params) {
    return match_validated(left, right, params);
}

ValidatedDisparity frame_of(const StreamResult& result, std::size_t first, int width, int height) {
    return assemble_validated(result.outputs, first, width, height);
}

// The small configuration, frame by frame (tb_cosim.hpp).
class Cosim : public tb::Cosim {
  public:
    Cosim() : tb::Cosim(small()) {}
};

using tb::RandomCase;

class RandomPairs : public tb::RandomPairTest {};

TEST_P(RandomPairs, EveryPixelEqualsTheModel) {
    const MatchParams params{labels(c.ndisp), c.window, fx::kDefaultSigma, c.use_ca};
    Cosim cosim;
    const ValidatedDisparity rtl = cosim.run(pair.left, pair.right, params, traffic);
    EXPECT_TRUE(same_validated(expected(pair.left, pair.right, params), rtl));
}

INSTANTIATE_TEST_SUITE_P(
    Stereo, RandomPairs,
    ::testing::Values(RandomCase{64, 48, 16, 5, true, 0.0, 0.0},
                      RandomCase{64, 48, 16, 5, true, 0.3, 0.3},
                      RandomCase{64, 48, 16, 5, false, 0.2, 0.5},
                      RandomCase{37, 23, 9, 5, true, 0.1, 0.1},   // odd size, fewer labels
                      RandomCase{41, 29, 16, 3, true, 0.2, 0.2},  // smaller runtime window
                      RandomCase{23, 17, 4, 1, false, 0.0, 0.3},  // 1x1 window
                      RandomCase{63, 47, 16, 5, true, 0.5, 0.0}));

// ---- Stage 6: signed range, uniqueness, left-right check, sub-pixel -------------------------
struct Stage6Case {
    int width, height, ndisp, window;
    bool use_ca;
    int min_disp;
    int uniqueness;  // -1: off
    int lr;          // -1: off
    bool subpixel;
    int shift;  // true disparity of the synthetic pair (negative: the right image leads)
    double gap, stall;
};

void PrintTo(const Stage6Case& c, std::ostream* out) {
    *out << c.width << "x" << c.height << " ndisp " << c.ndisp << " window " << c.window
         << (c.use_ca ? " CA" : " no CA") << " min_disp " << c.min_disp << " uniqueness "
         << c.uniqueness << " lr " << c.lr << (c.subpixel ? " subpixel" : "") << " shift "
         << c.shift << " gap " << c.gap << " stall " << c.stall;
}

MatchParams stage6_params(const Stage6Case& c) {
    MatchParams params{labels(c.ndisp), c.window, fx::kDefaultSigma, c.use_ca};
    params.min_disp = c.min_disp;
    params.validation.uniqueness = c.uniqueness >= 0;
    params.validation.uniqueness_ratio = std::max(c.uniqueness, 0);
    params.validation.left_right = c.lr >= 0;
    params.validation.lr_tolerance = std::max(c.lr, 0);
    params.validation.subpixel = c.subpixel;
    return params;
}

class Stage6Pairs : public ::testing::TestWithParam<Stage6Case> {};

TEST_P(Stage6Pairs, EveryPixelEqualsTheModel) {
    const Stage6Case c = GetParam();
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    const MatchParams params = stage6_params(c);
    // The comparison must have something to compare: the checks it enables reject some pixels,
    // and sub-pixel refinement moves some disparities off the integer grid (with more than 3
    // labels; with one label nothing can fail). A noisy random pair almost always does both; the
    // rare one that does not (tolerance 0 on a clean shift, say) is redrawn, a few times at most.
    const auto exercises = [&](const ValidatedDisparity& model) {
        std::size_t rejected = 0;
        std::size_t fractional = 0;
        for (std::size_t i = 0; i < model.fixed.size(); ++i) {
            rejected += model.reason[i] > fx::kReasonBorder ? 1 : 0;
            fractional += model.fixed[i] % fx::kSubpixelScale != 0 ? 1 : 0;
        }
        return (!(c.uniqueness >= 0 || c.lr >= 0) || labels(c.ndisp) <= 3 || rejected > 0) &&
               (!c.subpixel || labels(c.ndisp) <= 2 || fractional > 0);
    };
    io::ImagePair pair = test::shifted_pair(c.width, c.height, 3, c.shift, 25, rng);
    ValidatedDisparity model = expected(pair.left, pair.right, params);
    for (int draw = 1; draw < 5 && !exercises(model); ++draw) {
        pair = test::shifted_pair(c.width, c.height, 3, c.shift, 25, rng);
        model = expected(pair.left, pair.right, params);
    }
    // A case written for more labels than the configuration has (capped by labels()) was not
    // chosen to exercise its checks with fewer: it is compared all the same.
    if (labels(c.ndisp) == c.ndisp) {
        EXPECT_TRUE(exercises(model)) << "no pair of five exercised the enabled checks";
    }
    Cosim cosim;
    EXPECT_TRUE(
        same_validated(model, cosim.run(pair.left, pair.right, params, {c.gap, c.stall, seed})));
}

constexpr int kMaxMin = table::kDefaultMaxMinDisp;
INSTANTIATE_TEST_SUITE_P(
    Stereo, Stage6Pairs,
    ::testing::Values(
        // All on, stalls both ways.
        Stage6Case{64, 48, 16, 5, true, 0, 10, 1, true, 3, 0.2, 0.2},
        // Negative ranges: the left pixel waits K steps; true disparity negative.
        Stage6Case{64, 48, 16, 5, true, -kMaxMin, 10, 1, true, -3, 0.1, 0.3},
        Stage6Case{63, 47, 16, 5, true, -5, -1, 0, true, 2, 0.3, 0.1},
        // Positive minimum disparity.
        Stage6Case{64, 48, 16, 5, false, kMaxMin, 25, 2, false, 12, 0.2, 0.2},
        Stage6Case{37, 23, 9, 3, true, 2, -1, -1, true, 5, 0.1, 0.1},
        // Each check alone; odd sizes; few labels (no second cost for N <= 3).
        Stage6Case{41, 29, 16, 5, true, -1, 30, -1, false, 4, 0.2, 0.0},
        Stage6Case{33, 21, 12, 5, false, 0, -1, 0, false, 3, 0.0, 0.4},
        Stage6Case{23, 17, 3, 1, false, -1, 50, 1, true, 0, 0.1, 0.1},
        Stage6Case{23, 17, 1, 3, true, -2, 10, 0, true, -2, 0.2, 0.2}));

// Without stalls a frame takes W*H + latency + 1 cycles, the latency growing by K = -min_disp.
// Each frame starts from an idle core (a fresh reset): right after a frame the input slice takes
// the next frame's first beat while the label-group counter still runs (G > 1), and those clocks
// count from that beat on.
TEST(Throughput, NegativeMinimumDisparityAddsItsDelay) {
    std::mt19937 rng(tb::test_seed());
    const TopConfig& point = small();
    const auto [left, right] = test::shifted_pair(point.width, point.height, 3, -2, 10, rng);
    for (const int min_disp : {-kMaxMin, -3, 4}) {
        Cosim cosim;
        MatchParams params{point.ndisp, point.window, fx::kDefaultSigma, true};
        params.min_disp = min_disp;
        params.validation.left_right = true;
        StreamResult result;
        EXPECT_TRUE(same_validated(expected(left, right, params),
                                   cosim.run(left, right, params, {}, &result)));
        EXPECT_EQ(result.cycles,
                  documented_cycles(point.width, point.height, point.window, min_disp))
            << "min_disp " << min_disp;
    }
}

// Frames of different sizes and stage-6 configurations back to back in one stream, without
// reset: the configuration is latched at each start of frame.
TEST(Framing, BackToBackFramesWithDifferentStage6Configurations) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    Cosim cosim;
    const Stage6Case cases[] = {
        {32, 24, 8, 5, true, -kMaxMin, 10, 1, true, -4, 0, 0},
        {20, 30, 8, 5, true, 3, 20, 0, false, 5, 0, 0},
        {64, 48, 16, 5, false, -2, -1, 2, true, 1, 0, 0},  // labels(16) below
        {13, 9, 4, 3, true, 0, -1, -1, false, 1, 0, 0},
        {40, 12, 16, 3, true, -6, 5, 1, true, -5, 0, 0},
    };
    for (const Stage6Case& c : cases) {
        const auto [left, right] = test::shifted_pair(c.width, c.height, 3, c.shift, 15, rng);
        const MatchParams params = stage6_params(c);
        EXPECT_TRUE(same_validated(expected(left, right, params),
                                   cosim.run(left, right, params, {0.1, 0.1, seed})))
            << ::testing::PrintToString(c);
    }
}

TEST(Framing, ResetInTheMiddleOfAStage6Frame) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    const Stage6Case c{64, 48, 16, 5, true, -kMaxMin, 10, 1, true, -3, 0, 0};
    const MatchParams params = stage6_params(c);
    const auto [left, right] = test::shifted_pair(64, 48, 3, -3, 15, rng);
    Cosim cosim;
    cosim.reset_mid_frame(left, right, params, 2 * 64 * 48 / 3, 200, {0.2, 0.2, seed});
    const auto [left2, right2] = test::shifted_pair(64, 48, 3, 6, 15, rng);
    MatchParams params2 = params;
    params2.min_disp = 2;
    EXPECT_TRUE(same_validated(expected(left2, right2, params2),
                               cosim.run(left2, right2, params2, {0.2, 0.2, seed})));
}

// A frame under the out-of-range configuration `wide`: the core raises the clamped-configuration
// status bit and matches as the model does with `clamped`, what it clamps `wide` to.
void expect_clamped(Cosim& cosim, const Image& left, const Image& right, const CoreParams& wide,
                    const MatchParams& clamped) {
    cosim.sim().set_params(wide);
    const auto beats = frame_beats(left, right);
    const StreamResult result = cosim.sim().stream(beats, beats.size(), {}, 100000);
    ASSERT_TRUE(result.completed);
    EXPECT_EQ(result.status & (1U << table::kStatusConfigClamped),
              1U << table::kStatusConfigClamped);
    EXPECT_TRUE(same_validated(expected(left, right, clamped),
                               frame_of(result, 0, left.width, left.height)));
}

TEST(BadInput, OutOfRangeMinimumDisparityIsClampedAndFlagged) {
    std::mt19937 rng(tb::test_seed());
    const auto [left, right] = test::shifted_pair(64, 48, 3, -3, 5, rng);
    for (const int sign : {-1, 1}) {
        Cosim cosim;
        MatchParams params{small().ndisp, 5, fx::kDefaultSigma, true};
        params.validation.left_right = true;
        CoreParams wide{64, 48, params};
        wide.match.min_disp = sign * (kMaxMin + 7);
        params.min_disp = sign * kMaxMin;  // what the core clamps to
        expect_clamped(cosim, left, right, wide, params);
    }
}

TEST(Extremes, ConstantImages) {
    Cosim cosim;
    const std::uint32_t seed = tb::test_seed();
    for (const auto& [l, r, left, right] : test::constant_pairs(64, 48, 3)) {
        const MatchParams params{labels(16), 5, fx::kDefaultSigma, true};
        EXPECT_TRUE(same_validated(expected(left, right, params),
                                   cosim.run(left, right, params, {0.2, 0.2, seed})))
            << "left " << l << " right " << r;
    }
}

TEST(Extremes, GreyInputIsMatchedAsRgb) {
    std::mt19937 rng(tb::test_seed());
    const auto [left, right] = test::shifted_pair(48, 32, 1, 2, 10, rng);
    const MatchParams params{labels(12), 5, fx::kDefaultSigma, true};
    Cosim cosim;
    EXPECT_TRUE(same_validated(expected(left, right, params), cosim.run(left, right, params, {})));
}

struct RealCase {
    const char* name;
    std::filesystem::path left, right;
    int downscale, x0, y0, ndisp;
};

void PrintTo(const RealCase& c, std::ostream* out) {
    *out << c.name;
}

class RealPairs : public ::testing::TestWithParam<RealCase> {};

TEST_P(RealPairs, EveryPixelEqualsTheModel) {
    const RealCase c = GetParam();
    const auto pair = tb::real_crop(c.left, c.right, c.downscale, c.x0, c.y0);
    if (!pair) {
        GTEST_SKIP() << c.name << " not found";
    }
    const std::uint32_t seed = tb::test_seed();
    Cosim cosim;
    for (const bool use_ca : {true, false}) {
        const MatchParams params{labels(c.ndisp), 5, fx::kDefaultSigma, use_ca};
        EXPECT_TRUE(same_validated(expected(pair->left, pair->right, params),
                                   cosim.run(pair->left, pair->right, params, {0.1, 0.1, seed})))
            << c.name << " CA " << use_ca;
    }
    // Stage 6 on: a shifted range, every check and sub-pixel output.
    for (const int min_disp : {-3, 2}) {
        MatchParams params{labels(c.ndisp), 5, fx::kDefaultSigma, true};
        params.min_disp = min_disp;
        params.validation = {true, 15, true, 1, true};
        EXPECT_TRUE(same_validated(expected(pair->left, pair->right, params),
                                   cosim.run(pair->left, pair->right, params, {0.1, 0.1, seed})))
            << c.name << " stage 6, min_disp " << min_disp;
    }
}

INSTANTIATE_TEST_SUITE_P(
    Stereo, RealPairs,
    ::testing::Values(RealCase{"tsukuba", tb::middlebury("tsukuba", "left.png"),
                               tb::middlebury("tsukuba", "right.png"), 1, 150, 100, 16},
                      RealCase{"cones", tb::middlebury("cones", "left.png"),
                               tb::middlebury("cones", "right.png"), 2, 60, 60, 16},
                      RealCase{"aloe", io::aloe_dir() / "aloeL.jpg", io::aloe_dir() / "aloeR.jpg",
                               8, 50, 40, 16}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(Throughput, CyclesPerFrameWithoutStallsMatchTheDocumentedLatency) {
    std::mt19937 rng(tb::test_seed());
    const TopConfig& point = small();  // the configuration Cosim runs
    const auto [left, right] = test::shifted_pair(point.width, point.height, 3, 4, 10, rng);
    Cosim cosim;
    StreamResult result;
    (void)cosim.run(left, right, {point.ndisp, point.window, fx::kDefaultSigma, true}, {}, &result);
    const auto pixels = static_cast<std::uint64_t>(point.width) * point.height;
    const auto latency = static_cast<std::uint64_t>(
        table::pipeline_latency(point.width, point.window, point.ndisp, 0));
    const std::uint64_t expected = documented_cycles(point.width, point.height, point.window, 0);
    std::cout << "[cycles] " << point.width << "x" << point.height << " NDISP " << point.ndisp
              << " LANES " << point.lanes << ": " << result.cycles << " cycles, expected "
              << expected << " (" << table::clocks_per_step(point.ndisp, point.lanes)
              << " clocks per step, pixels " << pixels << " + latency " << latency << ")\n";
    // Exactly: the stage table's formula is what the RTL does.
    EXPECT_EQ(result.cycles, expected);
}

TEST(Framing, BackToBackFramesWithoutIdle) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    const MatchParams params{labels(16), 5, fx::kDefaultSigma, true};
    std::vector<std::pair<Image, Image>> frames;
    std::vector<InputBeat> beats;
    for (int f = 0; f < 3; ++f) {
        const Image left = test::random_image(64, 48, 3, rng);
        frames.emplace_back(left, test::shifted_copy(left, 2 + f, 15, rng));
        const auto frame = frame_beats(frames.back().first, frames.back().second);
        beats.insert(beats.end(), frame.begin(), frame.end());
    }
    Cosim cosim;
    cosim.sim().set_params({64, 48, params});
    const StreamResult result =
        cosim.sim().stream(beats, beats.size(), {0.1, 0.2, seed}, 50 * beats.size());
    ASSERT_TRUE(result.completed);
    EXPECT_EQ(result.protocol_error, "");
    EXPECT_EQ(result.status, 0U);
    for (int f = 0; f < 3; ++f) {
        const ValidatedDisparity rtl =
            frame_of(result, static_cast<std::size_t>(f) * 64 * 48, 64, 48);
        EXPECT_TRUE(same_validated(expected(frames[f].first, frames[f].second, params), rtl))
            << "frame " << f;
    }
}

// Frames of different sizes back to back, without reset: a taller frame after a shorter one
// must not mistake the previous frame's flush filler (rows >= its height) for its own pixels.
TEST(Framing, BackToBackFramesOfDifferentSizes) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    const MatchParams params{labels(8), 5, fx::kDefaultSigma, true};
    Cosim cosim;
    for (const auto& [width, height] : {std::pair{32, 12}, std::pair{32, 24}, std::pair{20, 30},
                                        std::pair{64, 48}, std::pair{13, 9}}) {
        const auto [left, right] = test::shifted_pair(width, height, 3, 3, 10, rng);
        EXPECT_TRUE(same_validated(expected(left, right, params),
                                   cosim.run(left, right, params, {0.1, 0.1, seed})))
            << width << "x" << height;
    }
}

TEST(Framing, ResetInTheMiddleOfAFrameThenACleanFrame) {
    const std::uint32_t seed = tb::test_seed();
    std::mt19937 rng(seed);
    const auto [left, right] = test::shifted_pair(64, 48, 3, 5, 15, rng);
    const MatchParams params{labels(16), 5, fx::kDefaultSigma, true};
    Cosim cosim;
    // Half a frame, with a few of its outputs already out, then reset.
    cosim.reset_mid_frame(left, right, params, 64 * 48 / 2, 100, {0.2, 0.2, seed});
    // A second frame with different content must come out exactly right.
    const auto [left2, right2] = test::shifted_pair(64, 48, 3, 7, 15, rng);
    EXPECT_TRUE(same_validated(expected(left2, right2, params),
                               cosim.run(left2, right2, params, {0.2, 0.2, seed})));
}

// The frame the malformed-stream tests spoil: a random 32x24 pair with 8 labels, its beats, and a
// fresh core configured for it.
struct SmallFrame {
    std::mt19937 rng{tb::test_seed()};
    io::ImagePair pair = test::shifted_pair(32, 24, 3, 3, 5, rng);
    MatchParams params{labels(8), 5, fx::kDefaultSigma, true};
    Cosim cosim;
    std::vector<InputBeat> beats = frame_beats(pair.left, pair.right);

    SmallFrame() { cosim.sim().set_params({32, 24, params}); }
    ValidatedDisparity model() const { return expected(pair.left, pair.right, params); }
    StreamResult stream(const std::vector<InputBeat>& input, std::uint64_t max_cycles) {
        return cosim.sim().stream(input, beats.size(), {}, max_cycles);
    }
};

TEST(BadInput, BeatsBeforeTheFirstStartOfFrameAreDropped) {
    SmallFrame frame;
    std::vector<InputBeat> stream(5, InputBeat{0x123456789ABCULL, false, false});  // no tuser
    stream.insert(stream.end(), frame.beats.begin(), frame.beats.end());
    const StreamResult result = frame.stream(stream, 100000);
    ASSERT_TRUE(result.completed);
    EXPECT_EQ(result.status, 0U);
    EXPECT_TRUE(same_validated(frame.model(), frame_of(result, 0, 32, 24)));
}

TEST(BadInput, MisplacedTlastAndTuserSetStatusBitsAndTheFrameStillCompletes) {
    SmallFrame frame;
    frame.beats[40].last = true;   // not a row end
    frame.beats[100].user = true;  // start of frame inside a frame
    const StreamResult result = frame.stream(frame.beats, 100000);
    EXPECT_TRUE(result.completed);  // one output per input pixel regardless
    EXPECT_EQ(result.status & 3U,
              (1U << table::kStatusEolMisplaced) | (1U << table::kStatusSofMisplaced));
}

TEST(BadInput, AStreamThatEndsEarlyNeverProducesAPartialFrameAndResetRecovers) {
    SmallFrame frame;
    const std::vector<InputBeat> cut(frame.beats.begin(), frame.beats.end() - 50);
    const StreamResult stalled = frame.stream(cut, 20000);
    EXPECT_FALSE(stalled.completed);
    EXPECT_LT(stalled.outputs.size(), frame.beats.size());
    frame.cosim.sim().reset();
    EXPECT_TRUE(same_validated(
        frame.model(), frame.cosim.run(frame.pair.left, frame.pair.right, frame.params, {})));
}

TEST(BadInput, OutOfRangeConfigurationIsFlaggedAndClamped) {
    std::mt19937 rng(tb::test_seed());
    const auto [left, right] = test::shifted_pair(64, 48, 3, 3, 5, rng);
    Cosim cosim;
    MatchParams params{small().ndisp, 5, fx::kDefaultSigma, true};
    cosim.sim().set_params({64, 48, params});
    // cfg_ndisp beyond NDISP: the core clamps to NDISP and raises status bit 2.
    CoreParams wide{64, 48, params};
    wide.match.ndisp = 40;
    wide.match.window = 5;
    expect_clamped(cosim, left, right, wide, params);
}

}  // namespace
}  // namespace stereo::sim
