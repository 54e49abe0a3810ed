// stereo_plane_stats (the hierarchical core's plane statistics, issue 45) against
// stereo::hierarchical::plane_statistics, bit for bit: random level maps and planes (slopes,
// offsets, tolerances), the full level of a real misaligned crop frame after frame with the
// host's PlaneTracker closing the loop, gaps between the winners, and an abandoned frame.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <verilated.h>
#include <verilated_fst_c.h>
#pragma GCC diagnostic pop

#include "Vstereo_plane_stats.h"
#include "stereo/hierarchical.hpp"
#include "stereo/hierarchical_plane.hpp"
#include "stereo_io/test_support.hpp"
#include "tb_real_pairs.hpp"
#include "tb_reset.hpp"
#include "verilated_harness.hpp"

namespace stereo::tb {
namespace {

namespace h = stereo::hierarchical;

// The module's default parameters, which the Verilated configuration builds.
constexpr int kVMin = -8;
constexpr int kVMax = 7;

class PlaneStats {
  public:
    PlaneStats() : harness_("plane_stats") { reset_stage(harness_); }

    // Streams `level` with `setting` (every pixel, or the first `pixels`), a gap of idle clocks
    // before a winner with probability `gap`; the statistics the module put out, or nothing when
    // it signalled no finished frame.
    std::optional<h::PlaneStatistics> stream(const h::LevelMap& level,
                                             const h::PlaneSetting& setting, double gap,
                                             std::mt19937& rng, int pixels = -1) {
        Vstereo_plane_stats& m = harness_.model();
        m.cfg_width = static_cast<std::uint16_t>(level.width);
        m.cfg_height = static_cast<std::uint16_t>(level.height);
        m.plane_a = static_cast<std::uint32_t>(static_cast<std::int32_t>(setting.plane.a));
        m.plane_b = static_cast<std::uint32_t>(static_cast<std::int32_t>(setting.plane.b));
        m.plane_c = static_cast<std::uint32_t>(static_cast<std::int32_t>(setting.plane.c));
        m.tolerance = static_cast<std::uint32_t>(setting.tolerance);
        std::bernoulli_distribution idle(gap);
        bool done = false;
        const int total = pixels < 0 ? level.width * level.height : pixels;
        for (int i = 0; i < total; ++i) {
            const int x = i % level.width;
            const int y = i / level.width;
            while (idle(rng)) {
                m.ce = 0;
                done = tick() || done;
            }
            const std::size_t p = level.index(x, y);
            m.ce = 1;
            m.in_x = static_cast<std::uint16_t>(x);
            m.in_y = static_cast<std::uint16_t>(y);
            m.in_valid = level.valid[p];
            m.in_d = static_cast<std::uint16_t>(level.disparity[p]);
            m.in_v = static_cast<std::uint8_t>(static_cast<std::int8_t>(level.vertical[p]));
            done = tick() || done;
        }
        m.ce = 0;
        done = tick() || done;
        if (!done) {
            return std::nullopt;
        }
        h::PlaneStatistics s;
        const auto value = [](std::uint64_t bits) { return static_cast<std::int64_t>(bits); };
        s.count = value(m.out_count);
        s.sum_x = value(m.out_sum_x);
        s.sum_y = value(m.out_sum_y);
        s.sum_xx = value(m.out_sum_xx);
        s.sum_xy = value(m.out_sum_xy);
        s.sum_yy = value(m.out_sum_yy);
        s.sum_v = value(m.out_sum_v);
        s.sum_xv = value(m.out_sum_xv);
        s.sum_yv = value(m.out_sum_yv);
        s.v_min = kVMin;
        for (int b = 0; b <= kVMax - kVMin; ++b) {
            m.hist_index = static_cast<std::uint8_t>(b);
            m.eval();
            s.histogram.push_back(m.hist_count);
        }
        return s;
    }

    void reset() { reset_stage(harness_); }

  private:
    bool tick() {
        harness_.tick();
        return harness_.model().out_done != 0;
    }

    sim::VerilatedHarness<Vstereo_plane_stats> harness_;
};

h::LevelMap random_level(int width, int height, std::mt19937& rng) {
    h::LevelMap level{width, height, std::vector<std::int16_t>(width * height, 0),
                      std::vector<std::int16_t>(width * height),
                      std::vector<std::uint8_t>(width * height)};
    std::uniform_int_distribution<int> offset(kVMin, kVMax);
    // Displacements up to beyond the width: some votes fall left of the image.
    std::uniform_int_distribution<int> displacement(0, width + 2);
    std::bernoulli_distribution valid(0.8);
    for (std::size_t p = 0; p < level.valid.size(); ++p) {
        level.disparity[p] = static_cast<std::int16_t>(displacement(rng));
        level.vertical[p] = static_cast<std::int16_t>(offset(rng));
        level.valid[p] = valid(rng) ? 1 : 0;
    }
    return level;
}

TEST(StereoPlaneStats, RandomLevelsAndPlanesEqualModel) {
    PlaneStats rtl;
    auto rng = test::seeded_rng(45);
    std::uniform_int_distribution<int> side(1, 64);
    std::uniform_int_distribution<std::int64_t> offset(-8 * h::kPlaneOne, 8 * h::kPlaneOne);
    std::uniform_int_distribution<std::int64_t> slope(-h::kPlaneOne / 8, h::kPlaneOne / 8);
    std::uniform_int_distribution<std::int64_t> tolerance(0, 4 * h::kPlaneOne);
    for (int frame = 0; frame < 40; ++frame) {
        const h::LevelMap level = random_level(side(rng), side(rng), rng);
        const h::PlaneSetting setting{h::Plane{offset(rng), slope(rng), slope(rng)},
                                      frame % 4 == 0 ? h::kFitTolerance : tolerance(rng)};
        SCOPED_TRACE("frame " + std::to_string(frame) + ": " + std::to_string(level.width) + "x" +
                     std::to_string(level.height));
        const auto out = rtl.stream(level, setting, frame % 2 == 0 ? 0.0 : 0.3, rng);
        ASSERT_TRUE(out.has_value()) << "no finished frame";
        EXPECT_EQ(*out, h::plane_statistics(level, setting, kVMin, kVMax));
    }
}

// An abandoned frame (stopped half way, then a reset; or cut short by the next start of frame)
// never reaches the outputs, and leaves nothing in the next frame's sums.
TEST(StereoPlaneStats, AbandonedFrameLeavesNothing) {
    PlaneStats rtl;
    auto rng = test::seeded_rng(46);
    const h::LevelMap first = random_level(30, 20, rng);
    const h::LevelMap second = random_level(28, 22, rng);
    const h::PlaneSetting setting{h::Plane{2 * h::kPlaneOne, 0, 0}, h::kFirstFitTolerance};
    EXPECT_FALSE(rtl.stream(first, setting, 0.2, rng, 300).has_value());
    rtl.reset();
    EXPECT_EQ(rtl.stream(second, setting, 0.2, rng),
              h::plane_statistics(second, setting, kVMin, kVMax));
    EXPECT_FALSE(rtl.stream(first, setting, 0.0, rng, 450).has_value());  // no reset: new frame
    EXPECT_EQ(rtl.stream(second, setting, 0.0, rng),
              h::plane_statistics(second, setting, kVMin, kVMax));
}

// The loop as the core and the host run it: the full level of a real crop whose right image is
// 2 rows lower, frame after frame, each frame's statistics from the RTL fed to PlaneTracker;
// the RTL's statistics equal the model's every frame, and the plane settles on the 2 rows.
TEST(StereoPlaneStats, RealFullLevelWithTheHostLoop) {
    const auto crop = tsukuba_crop();
    if (!crop) {
        GTEST_SKIP() << "Middlebury tsukuba not found";
    }
    Image right = crop->right;
    for (int y = right.height - 1; y >= 2; --y) {
        for (int x = 0; x < right.width; ++x) {
            for (int c = 0; c < right.channels; ++c) {
                right.at(x, y, c) = right.at(x, y - 2, c);
            }
        }
    }
    h::Params params;
    params.ndisp = 16;
    params.vrange = 16;
    params.cost = "census";
    h::CostCount count;
    const auto levels = h::match_levels(crop->left, right, params, count);
    PlaneStats rtl;
    auto rng = test::seeded_rng(47);
    h::PlaneTracker tracker;
    for (int frame = 0; frame < 4; ++frame) {
        const auto out = rtl.stream(levels[2], tracker.setting(), 0.1, rng);
        ASSERT_TRUE(out.has_value());
        ASSERT_EQ(*out, h::plane_statistics(levels[2], tracker.setting(), kVMin, kVMax))
            << "frame " << frame;
        tracker.update(*out);
    }
    EXPECT_EQ(h::plane_field(tracker.setting().plane, 32, 24, kVMin, kVMax)[12 * 32 + 16], 2);
}

}  // namespace
}  // namespace stereo::tb
