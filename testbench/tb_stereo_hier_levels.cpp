// stereo_hier_levels (the hierarchical search's three levels chained: pyramid, FIFOs, the
// quarter level predicting the half, the half the full; issue 45) against
// stereo::hierarchical::match_levels with the census cost, bit for bit: every full-level winner
// (d, v) and its validity. Random pairs moved vertically, a real crop moved down and to the side,
// CA on and off, an odd frame size, idle clocks on the input, frames back to back (the next
// frame's pixels offered while the levels still work on the last one) and a reset in the middle
// of a frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "stage_driver.hpp"  // first: it includes the Verilator runtime headers quietly

#include "Vstereo_hier_levels.h"
#include "stereo/catalogue.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/pipeline.hpp"
#include "stereo_io/test_support.hpp"
#include "tb_hier_pairs.hpp"
#include "tb_real_pairs.hpp"

namespace stereo::tb {
namespace {

namespace h = stereo::hierarchical;
using test::random_image;

// The module's defaults (the Verilated configuration): 128 wide, D = V = 16, windows 9 / 15 / 15.
constexpr int kMaxWidth = 128;
constexpr int kNdisp = 16;
constexpr int kVrange = 16;

h::Params search_params(bool use_ca) {
    return census_search(kNdisp, kVrange, use_ca);
}

struct Frame {
    Image left;
    Image right;
};

class LevelsSim {
  public:
    LevelsSim() : harness_("hier_levels") { reset(); }

    void reset() {
        harness_.model().in_valid = 0;
        harness_.pulse_reset();
    }

    // Streams the frames back to back (CA as `use_ca`), an idle clock before an input pixel with
    // probability `gap`; the full-level winners of each frame. With `abandon_after`, resets after
    // that many pixels of the first frame and returns nothing.
    std::vector<h::LevelMap> run(const std::vector<Frame>& frames, bool use_ca, double gap,
                                 std::mt19937& rng, long abandon_after = -1) {
        auto& m = harness_.model();
        m.cfg_use_ca = use_ca ? 1 : 0;
        const std::array<int, 3> windows = {h::kDefaultLevelWindows[0], h::kDefaultLevelWindows[1],
                                            h::kDefaultLevelWindows[2]};
        put_kernel(m.cfg_kernel_q, windows[0]);
        put_kernel(m.cfg_kernel_h, windows[1]);
        put_kernel(m.cfg_kernel_f, windows[2]);
        std::vector<h::LevelMap> out;
        std::vector<std::vector<std::uint8_t>> seen;
        std::vector<int> recorded(frames.size(), 0);
        for (const Frame& f : frames) {
            const std::size_t size = static_cast<std::size_t>(f.left.width) * f.left.height;
            out.push_back({f.left.width, f.left.height, std::vector<std::int16_t>(size),
                           std::vector<std::int16_t>(size), std::vector<std::uint8_t>(size, 0)});
            seen.emplace_back(size, 0);
        }
        // The setting is on the ports a clock before the first pixel (the module registers it).
        if (!frames.empty()) {
            m.cfg_width = static_cast<std::uint16_t>(frames[0].left.width);
            m.cfg_height = static_cast<std::uint16_t>(frames[0].left.height);
            m.in_valid = 0;
            harness_.tick();
        }
        std::bernoulli_distribution idle(gap);
        std::size_t in_frame = 0;   // the frame being fed
        std::size_t out_frame = 0;  // the frame whose winners come out
        long fed = 0;               // pixels of in_frame fed
        long total_fed = 0;
        long clock = 0;
        while (out_frame < frames.size()) {
            if (++clock > 400'000L * static_cast<long>(frames.size())) {
                ADD_FAILURE() << "frame " << out_frame << ": only " << recorded[out_frame]
                              << " winners came out (" << total_fed << " pixels in, in_ready "
                              << int{m.in_ready} << ", busy " << int{m.busy} << ")";
                return out;
            }
            const bool feeding = in_frame < frames.size();
            const bool offer = feeding && !idle(rng);
            if (feeding) {
                const Frame& f = frames[in_frame];
                const int x = static_cast<int>(fed % f.left.width);
                const int y = static_cast<int>(fed / f.left.width);
                m.cfg_width = static_cast<std::uint16_t>(f.left.width);
                m.cfg_height = static_cast<std::uint16_t>(f.left.height);
                m.in_x = static_cast<std::uint16_t>(x);
                m.in_y = static_cast<std::uint16_t>(y);
                m.in_left = rgb(f.left, x, y);
                m.in_right = rgb(f.right, x, y);
            }
            m.in_valid = offer ? 1 : 0;
            m.eval();
            if (m.out_valid != 0) {
                const auto x = static_cast<std::int16_t>(m.out_x);
                const auto y = static_cast<std::int16_t>(m.out_y);
                h::LevelMap& map = out[out_frame];
                const std::size_t p = static_cast<std::size_t>(y) * map.width + x;
                if (seen[out_frame][p] != 0) {
                    ADD_FAILURE() << "frame " << out_frame << ": pixel (" << x << ", " << y
                                  << ") came out twice";
                }
                seen[out_frame][p] = 1;
                map.disparity[p] = static_cast<std::int16_t>(m.out_d);
                map.vertical[p] = static_cast<std::int8_t>(m.out_v);
                map.valid[p] = m.out_ok;
                if (++recorded[out_frame] == map.width * map.height) {
                    last_frame_clocks_ = clock;
                    ++out_frame;
                }
            }
            const bool taken = offer && m.in_ready != 0;
            harness_.tick();
            if (taken) {
                ++total_fed;
                const Frame& f = frames[in_frame];
                if (++fed == static_cast<long>(f.left.width) * f.left.height) {
                    fed = 0;
                    ++in_frame;
                }
                if (total_fed == abandon_after) {
                    reset();
                    return {};
                }
            }
        }
        return out;
    }

    // Clocks from the first clock of the last run() to its last frame's last winner.
    long last_frame_clocks() const { return last_frame_clocks_; }

  private:
    long last_frame_clocks_ = 0;
    template <class Port>
    static void put_kernel(Port& port, int window) {
        const auto taps = gaussian_kernel(window, h::default_level(window).sigma);
        for (int i = 0; i < window; ++i) {
            put_bits(port, i * table::kTapBits, table::kTapBits,
                     static_cast<std::uint64_t>(taps[static_cast<std::size_t>(i)]));
        }
    }
    static std::uint32_t rgb(const Image& image, int x, int y) {
        return static_cast<std::uint32_t>(image.at(x, y, 0)) << 16 |
               static_cast<std::uint32_t>(image.at(x, y, 1)) << 8 | image.at(x, y, 2);
    }

    sim::VerilatedHarness<Vstereo_hier_levels> harness_;
};

h::LevelMap model_full_level(const Frame& frame, bool use_ca) {
    h::CostCount count;
    return h::match_levels(frame.left, frame.right, search_params(use_ca), count)[2];
}

Frame random_moved_pair(int width, int height, int dx, int dy, std::mt19937& rng) {
    const Image left = random_image(width, height, 3, rng);
    return {left, moved(left, -dx, dy)};
}

TEST(StereoHierLevels, RandomPairsEqualModelFrameAfterFrame) {
    std::mt19937 rng(4511);
    LevelsSim rtl;
    const std::vector<Frame> frames = {random_moved_pair(128, 96, 5, 3, rng),
                                       random_moved_pair(122, 90, 9, -5, rng),
                                       random_moved_pair(128, 96, 2, 0, rng)};
    for (const bool use_ca : {true, false}) {
        const auto out = rtl.run(frames, use_ca, use_ca ? 0.2 : 0.0, rng);
        ASSERT_EQ(out.size(), frames.size());
        for (std::size_t i = 0; i < frames.size(); ++i) {
            expect_levels_equal(out[i], model_full_level(frames[i], use_ca),
                                "frame " + std::to_string(i) + (use_ca ? " CA" : " no CA"));
        }
    }
}

TEST(StereoHierLevels, ResetInTheMiddleOfAFrame) {
    std::mt19937 rng(4512);
    LevelsSim rtl;
    const Frame frame = random_moved_pair(128, 96, 4, 2, rng);
    EXPECT_TRUE(rtl.run({frame}, true, 0.1, rng, 128 * 60).empty());
    const auto out = rtl.run({frame}, true, 0.1, rng);
    ASSERT_EQ(out.size(), 1U);
    expect_levels_equal(out[0], model_full_level(frame, true), "after the reset");
}

// A Tsukuba crop (128x96) whose right image is moved down 4 rows: the chained levels find it.
TEST(StereoHierLevels, RealCropEqualsModel) {
    const auto left_file = middlebury("tsukuba", "left.png");
    const auto right_file = middlebury("tsukuba", "right.png");
    if (!std::filesystem::exists(left_file) || !std::filesystem::exists(right_file)) {
        GTEST_SKIP() << "Middlebury tsukuba not found";
    }
    const auto pair = io::crop(io::load_pair(left_file, right_file, 1), 120, 100, kMaxWidth, 96);
    const Frame frame{pair.left, moved(pair.right, 0, 4)};
    std::mt19937 rng(4513);
    LevelsSim rtl;
    const auto out = rtl.run({frame}, true, 0.0, rng);
    ASSERT_EQ(out.size(), 1U);
    const h::LevelMap model = model_full_level(frame, true);
    expect_levels_equal(out[0], model, "tsukuba");
    // Without input gaps: the clocks from the first pixel to the last winner, against W x H.
    const double ratio = static_cast<double>(rtl.last_frame_clocks()) / (kMaxWidth * 96);
    std::cout << "hier_levels: " << rtl.last_frame_clocks() << " clocks for a 128x96 frame ("
              << ratio << " x W x H)\n";
    RecordProperty("clocks_per_frame", static_cast<int>(rtl.last_frame_clocks()));
    // The full level takes 9 / LANES_F clocks a pixel (the module's default LANES_F = 3, one
    // candidate row a clock); its wait and flush (about 73 rows) add less than one more.
    constexpr int kFullLevelGroups = 9 / 3;
    EXPECT_LT(ratio, kFullLevelGroups + 1.0)
        << "the levels should take about 9 / LANES_F clocks a pixel";
    const test::ValidCount count = test::count_valid_at(model.valid, model.vertical, 4);
    EXPECT_GT(2 * count.at_value, count.valid) << "the full level should find the 4-row move";
}

}  // namespace
}  // namespace stereo::tb
