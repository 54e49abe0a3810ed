// stereo_hier_level (one level of the hierarchical 2-D search, issue 45) against
// stereo::hierarchical::match_level with the census cost, bit for bit: every pixel's winning
// displacement (d, v) and validity. The quarter level (the whole 4 x 4 range of a 128x96 frame
// with D = V = 16) and the half level (3x3 around predictions): random pairs and random
// predictions (bases at both ends of the range), pairs moved vertically so that the winners
// leave v = 0, a real crop with the model's quarter level predicting the half level, CA on and
// off, odd frame sizes, idle clocks between steps, frames one after another with their own sizes,
// and a reset in the middle of a frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "stage_driver.hpp"  // first: it includes the Verilator runtime headers quietly

#include "Vstereo_hier_level_quarter.h"
#include "Vstereo_hier_level_refine.h"
#include "stereo/catalogue.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/pipeline.hpp"
#include "stereo_io/test_support.hpp"
#include "tb_hier_pairs.hpp"
#include "tb_real_pairs.hpp"
#include "tb_reset.hpp"

namespace stereo::tb {
namespace {

namespace h = stereo::hierarchical;
using test::random_image;

// The search the two configurations belong to: a 128x96 frame, D = V = 16 (stage_table.hpp).
constexpr int kFrameWidth = 128;
constexpr int kFrameHeight = 96;
h::Params search_params(bool use_ca) {
    return census_search(16, 16, use_ca);
}

// One level as its Verilated configuration was built: the level's factor (4 or 2) and window.
template <class Model>
struct LevelBuild;
template <>
struct LevelBuild<Vstereo_hier_level_quarter> {
    static constexpr auto kConfig = table::verilated("Vstereo_hier_level_quarter").params;
    static constexpr int kFactor = 4;
};
template <>
struct LevelBuild<Vstereo_hier_level_refine> {
    static constexpr auto kConfig = table::verilated("Vstereo_hier_level_refine").params;
    static constexpr int kFactor = 2;
};

template <class Model>
class LevelSim {
  public:
    using Build = LevelBuild<Model>;
    static constexpr int kWindow = Build::kConfig.window;
    static constexpr int kMaxWidth = Build::kConfig.width;
    // Clocks per pixel step: the labels / LANES (the step at the last group, as stereo_top).
    static constexpr int kGroups = Build::kConfig.cols * Build::kConfig.rows / Build::kConfig.lanes;

    LevelSim() : harness_("hier_level") { reset_stage(harness_); }

    h::LevelParams level_params() const { return h::default_level(kWindow); }

    // Streams one frame with `grid`'s bases (ignored by the quarter level), idle clocks between
    // steps with probability `gap`; the winners the module put out. With `abandon_after`, stops
    // feeding after that many pixels and resets (a mid-frame reset): returns nothing.
    std::optional<h::LevelMap> run(const Image& left, const Image& right, const CandidateGrid& grid,
                                   bool use_ca, double gap, std::mt19937& rng,
                                   int abandon_after = -1) {
        Model& m = harness_.model();
        const int width = left.width;
        const int height = left.height;
        m.cfg_width = static_cast<std::uint16_t>(width);
        m.cfg_height = static_cast<std::uint16_t>(height);
        m.cfg_use_ca = use_ca ? 1 : 0;
        const auto kernel = gaussian_kernel(kWindow, level_params().sigma);
        for (int i = 0; i < kWindow; ++i) {
            put_bits(m.cfg_kernel, i * table::kTapBits, table::kTapBits,
                     static_cast<std::uint64_t>(kernel[static_cast<std::size_t>(i)]));
        }
        h::LevelMap out{width, height, std::vector<std::int16_t>(grid_size(width, height)),
                        std::vector<std::int16_t>(grid_size(width, height)),
                        std::vector<std::uint8_t>(grid_size(width, height), 0)};
        std::vector<std::uint8_t> seen(grid_size(width, height), 0);
        int recorded = 0;
        const auto base_of = [&](std::int16_t x, std::int16_t y) {
            const bool inside = x >= 0 && x < width && y >= 0 && y < height;
            const std::size_t g = inside ? grid.at(static_cast<std::size_t>(y) * width + x) : 0;
            return std::pair<int, int>{grid.base_d[g], grid.base_v[g]};
        };
        std::bernoulli_distribution idle(gap);
        const long limit = static_cast<long>(width) * (height + 64) + 4096;
        long step = 0;
        bool stepped = false;
        for (long clock = 0; recorded < width * height; ++clock) {
            if (clock > 20L * kGroups * limit) {
                ADD_FAILURE() << "only " << recorded << " of " << width * height
                              << " winners came out";
                return out;
            }
            const auto [req_d, req_v] =
                base_of(static_cast<std::int16_t>(m.req_x), static_cast<std::int16_t>(m.req_y));
            m.in_base_d = static_cast<std::uint8_t>(req_d);
            m.in_base_v = static_cast<std::uint8_t>(req_v);
            const auto out_x = static_cast<std::int16_t>(m.out_x);
            const auto out_y = static_cast<std::int16_t>(m.out_y);
            const auto [out_d, out_v] = base_of(out_x, out_y);
            m.out_base_d = static_cast<std::uint8_t>(out_d);
            m.out_base_v = static_cast<std::uint8_t>(out_v);
            // Groups 0 .. G-2 of a step: every stage works on one group of labels, no step.
            if (group_ < kGroups - 1) {
                m.ce = 0;
                m.group = static_cast<std::uint8_t>(group_);
                harness_.tick();
                ++group_;
                continue;  // `stepped` holds: the winner stays until the next step
            }
            m.group = static_cast<std::uint8_t>(kGroups - 1);
            m.eval();
            if (stepped && out_x >= 0 && out_x < width && out_y >= 0 && out_y < height) {
                const std::size_t p = static_cast<std::size_t>(out_y) * width + out_x;
                if (seen[p] != 0) {
                    ADD_FAILURE() << "pixel (" << out_x << ", " << out_y << ") came out twice";
                }
                seen[p] = 1;
                ++recorded;
                out.disparity[p] = static_cast<std::int16_t>(m.out_d);
                out.vertical[p] = static_cast<std::int8_t>(m.out_v);
                out.valid[p] = m.out_valid;
            }
            stepped = !idle(rng);
            if (abandon_after >= 0 && step == abandon_after) {
                reset_stage(harness_);
                return std::nullopt;
            }
            m.ce = stepped ? 1 : 0;
            if (stepped) {
                group_ = 0;
                const long x = step % width;
                const long y = step / width;
                const bool pixel = y < height;
                m.in_x = static_cast<std::uint16_t>(x);
                m.in_y = static_cast<std::uint16_t>(y);
                m.in_left = pixel ? rgb(left, static_cast<int>(x), static_cast<int>(y)) : 0;
                m.in_right = pixel ? rgb(right, static_cast<int>(x), static_cast<int>(y)) : 0;
                ++step;
            }
            harness_.tick();
        }
        // The caller's frame boundary: the stages' coordinates hold flush rows, cleared as
        // stereo_top clears them when a frame's last result has left.
        reset_stage(harness_);
        return out;
    }

  private:
    static std::size_t grid_size(int width, int height) {
        return static_cast<std::size_t>(width) * height;
    }
    static std::uint32_t rgb(const Image& image, int x, int y) {
        return static_cast<std::uint32_t>(image.at(x, y, 0)) << 16 |
               static_cast<std::uint32_t>(image.at(x, y, 1)) << 8 | image.at(x, y, 2);
    }

    sim::VerilatedHarness<Model> harness_;
    int group_ = kGroups - 1;  // the group of the next clock (after a reset: the last)
};

template <class Model>
h::LevelMap model_level(const Image& left, const Image& right, const CandidateGrid& grid,
                        bool use_ca) {
    std::int64_t count = 0;
    return h::match_level(left, right, grid, h::default_level(LevelSim<Model>::kWindow), use_ca,
                          CaNeighbours::horizontal, count, search_params(use_ca).cost);
}

// One frame through `rtl` whose winners must equal the model's level: the RTL's winners, none when
// the module put out no frame (the caller's failure).
template <class Model>
std::optional<h::LevelMap> run_equal_to_model(LevelSim<Model>& rtl, const Image& left,
                                              const Image& right, const CandidateGrid& grid,
                                              bool use_ca, double gap, std::mt19937& rng,
                                              const std::string& what) {
    std::optional<h::LevelMap> out = rtl.run(left, right, grid, use_ca, gap, rng);
    if (out) {
        expect_levels_equal(*out, model_level<Model>(left, right, grid, use_ca), what);
    }
    return out;
}

// A coarse level of random winners for the refinement level of `width` x `height`.
h::LevelMap random_coarse(int width, int height, const h::SearchRange& coarse_range,
                          std::mt19937& rng) {
    const int cw = width / 2;
    const int ch = height / 2;
    std::uniform_int_distribution<int> d(coarse_range.d_min, coarse_range.d_max);
    std::uniform_int_distribution<int> v(coarse_range.v_min, coarse_range.v_max);
    h::LevelMap coarse{cw, ch, std::vector<std::int16_t>(static_cast<std::size_t>(cw) * ch),
                       std::vector<std::int16_t>(static_cast<std::size_t>(cw) * ch),
                       std::vector<std::uint8_t>(static_cast<std::size_t>(cw) * ch, 1)};
    for (std::size_t p = 0; p < coarse.disparity.size(); ++p) {
        coarse.disparity[p] = static_cast<std::int16_t>(d(rng));
        coarse.vertical[p] = static_cast<std::int16_t>(v(rng));
    }
    return coarse;
}

using Quarter = LevelSim<Vstereo_hier_level_quarter>;
using Refine = LevelSim<Vstereo_hier_level_refine>;

const h::SearchRange kQuarterRange = h::level_range(search_params(true), 4);
const h::SearchRange kHalfRange = h::level_range(search_params(true), 2);

TEST(StereoHierLevel, ConfigurationsAreTheSearchsLevels) {
    // The Verilated parameters are those of the 128x96, D = V = 16 search's levels.
    constexpr auto quarter = Quarter::Build::kConfig;
    EXPECT_EQ(quarter.width, kFrameWidth / 4);
    EXPECT_EQ(quarter.cols, kQuarterRange.d_max - kQuarterRange.d_min + 1);
    EXPECT_EQ(quarter.rows, kQuarterRange.v_max - kQuarterRange.v_min + 1);
    EXPECT_EQ(quarter.v_min, kQuarterRange.v_min);
    EXPECT_EQ(quarter.v_max, kQuarterRange.v_max);
    EXPECT_EQ(quarter.window, h::kDefaultLevelWindows[0]);
    constexpr auto half = Refine::Build::kConfig;
    EXPECT_EQ(half.width, kFrameWidth / 2);
    EXPECT_EQ(half.v_min, kHalfRange.v_min);
    EXPECT_EQ(half.v_max, kHalfRange.v_max);
    EXPECT_EQ(half.window, h::kDefaultLevelWindows[1]);
}

TEST(StereoHierLevel, QuarterLevelRandomPairsEqualModel) {
    std::mt19937 rng(4501);
    Quarter rtl;
    struct Case {
        int width, height, dy;
        bool use_ca;
        double gap;
    };
    for (const Case& c :
         {Case{32, 24, 0, true, 0.0}, Case{32, 24, -2, true, 0.3}, Case{32, 24, 1, false, 0.0},
          Case{23, 17, 1, true, 0.2}, Case{13, 24, -1, false, 0.1}}) {
        const Image left = random_image(c.width, c.height, 3, rng);
        const Image right = random_image(c.width, c.height, 3, rng);
        // Half the pairs are the left image moved by dy rows (winners away from v = 0).
        const Image shifted = moved(left, 0, c.dy);
        for (const Image* r : {&right, &shifted}) {
            const CandidateGrid grid = h::full_grid(c.width, c.height, kQuarterRange);
            ASSERT_TRUE(run_equal_to_model(
                rtl, left, *r, grid, c.use_ca, c.gap, rng,
                std::to_string(c.width) + "x" + std::to_string(c.height) + " dy " +
                    std::to_string(c.dy) + (r == &shifted ? " moved" : " random")));
        }
    }
}

TEST(StereoHierLevel, HalfLevelRandomPredictionsEqualModel) {
    std::mt19937 rng(4502);
    Refine rtl;
    struct Case {
        int width, height, dy;
        bool use_ca;
        double gap;
    };
    for (const Case& c : {Case{64, 48, 0, true, 0.0}, Case{64, 48, 3, true, 0.25},
                          Case{64, 48, -4, false, 0.0}, Case{41, 35, 2, true, 0.1}}) {
        const Image left = random_image(c.width, c.height, 3, rng);
        const Image right = moved(left, 0, c.dy);
        const auto coarse = random_coarse(c.width, c.height, kQuarterRange, rng);
        const CandidateGrid grid = h::refine_grid(coarse, c.width, c.height, kHalfRange);
        ASSERT_TRUE(run_equal_to_model(rtl, left, right, grid, c.use_ca, c.gap, rng,
                                       std::to_string(c.width) + "x" + std::to_string(c.height)));
    }
}

TEST(StereoHierLevel, FramesOneAfterAnotherAndAResetMidFrame) {
    std::mt19937 rng(4503);
    Refine rtl;
    const Image big_left = random_image(64, 48, 3, rng);
    const Image big_right = moved(big_left, 0, 2);
    const auto coarse = random_coarse(64, 48, kQuarterRange, rng);
    const CandidateGrid grid = h::refine_grid(coarse, 64, 48, kHalfRange);
    // A frame abandoned half-way by a reset, then frames of other sizes.
    EXPECT_FALSE(rtl.run(big_left, big_right, grid, true, 0.1, rng, 64 * 30).has_value());
    for (const auto& [width, height] : {std::pair{64, 48}, std::pair{30, 20}, std::pair{64, 48}}) {
        const Image left = random_image(width, height, 3, rng);
        const Image right = moved(left, 0, -3);
        const auto small = random_coarse(width, height, kQuarterRange, rng);
        const CandidateGrid g = h::refine_grid(small, width, height, kHalfRange);
        ASSERT_TRUE(run_equal_to_model(rtl, left, right, g, true, 0.05, rng,
                                       std::to_string(width) + "x" + std::to_string(height)));
    }
}

// A real crop (Tsukuba, 128x96 at full size) with its right image moved down 4 rows: the RTL
// quarter level equals the model's, and the RTL half level, predicted by it, equals the model's.
TEST(StereoHierLevel, RealCropQuarterPredictsHalf) {
    const auto left_file = middlebury("tsukuba", "left.png");
    const auto right_file = middlebury("tsukuba", "right.png");
    if (!std::filesystem::exists(left_file) || !std::filesystem::exists(right_file)) {
        GTEST_SKIP() << "Middlebury tsukuba not found";
    }
    const auto pair =
        io::crop(io::load_pair(left_file, right_file, 1), 120, 100, kFrameWidth, kFrameHeight);
    const Image left = pair.left;
    const Image right = moved(pair.right, 0, 4);
    std::mt19937 rng(4504);
    const Image quarter_left = h::downscale_area(left, 4);
    const Image quarter_right = h::downscale_area(right, 4);
    const CandidateGrid quarter_grid =
        h::full_grid(quarter_left.width, quarter_left.height, kQuarterRange);
    Quarter quarter;
    const auto quarter_out = run_equal_to_model(quarter, quarter_left, quarter_right, quarter_grid,
                                                true, 0.1, rng, "quarter");
    ASSERT_TRUE(quarter_out.has_value());

    const Image half_left = h::downscale_area(left, 2);
    const Image half_right = h::downscale_area(right, 2);
    const CandidateGrid half_grid =
        h::refine_grid(*quarter_out, half_left.width, half_left.height, kHalfRange);
    Refine half;
    const auto half_out =
        run_equal_to_model(half, half_left, half_right, half_grid, true, 0.1, rng, "half");
    ASSERT_TRUE(half_out.has_value());
    // The moved pair is found: most valid half-level winners (the RTL's, equal to the model's)
    // have v = 2 (4 rows at full size).
    const test::ValidCount count = test::count_valid_at(half_out->valid, half_out->vertical, 2);
    EXPECT_GT(count.valid, 0);
    EXPECT_GT(2 * count.at_value, count.valid);
}

}  // namespace
}  // namespace stereo::tb
