// stereo_downscale (the hierarchical search's pyramid, issue 45) against
// stereo::hierarchical::downscale_area, bit for bit: the half and the quarter image of random
// frames of every size up to the configuration's width (sizes that are not multiples of the
// factor included), of a real crop, with random gaps between the pixels (ce low), back-to-back
// frames, and a reset in the middle of a frame followed by a whole frame.
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

#include "Vstereo_downscale2.h"
#include "Vstereo_downscale4.h"
#include "stereo/hierarchical.hpp"
#include "stereo/stage_table.hpp"
#include "stereo_io/test_support.hpp"
#include "tb_real_pairs.hpp"
#include "tb_reset.hpp"
#include "verilated_harness.hpp"

namespace stereo::tb {
namespace {

// One output block: its coordinates and the packed RGB mean (channel c at bits 8c).
struct Block {
    int x;
    int y;
    std::uint32_t pixel;
    bool operator==(const Block&) const = default;
};

std::uint32_t packed(const Image& image, int x, int y) {
    std::uint32_t word = 0;
    for (int c = 0; c < 3; ++c) {
        word |= static_cast<std::uint32_t>(image.at(x, y, image.channels == 3 ? c : 0)) << (8 * c);
    }
    return word;
}

// What the model says: every block of downscale_area in raster order.
std::vector<Block> expected_blocks(const Image& image, int factor) {
    const Image small = hierarchical::downscale_area(image, factor);
    std::vector<Block> blocks;
    for (int y = 0; y < small.height; ++y) {
        for (int x = 0; x < small.width; ++x) {
            blocks.push_back({x, y, packed(small, x, y)});
        }
    }
    return blocks;
}

std::int16_t signed_coord(std::uint32_t bits) {
    return static_cast<std::int16_t>(static_cast<std::uint16_t>(bits));
}

template <typename Model>
class Downscaler {
  public:
    explicit Downscaler(const char* name) : harness_(name) { reset_stage(harness_); }

    // Streams `rows` rows of `image` (all of them by default) with a gap of idle clocks before a
    // pixel with probability `gap`; the blocks that came out.
    std::vector<Block> stream(const Image& image, double gap, std::mt19937& rng, int rows = -1) {
        Model& m = harness_.model();
        m.cfg_width = static_cast<std::uint16_t>(image.width);
        m.cfg_height = static_cast<std::uint16_t>(image.height);
        std::bernoulli_distribution idle(gap);
        std::vector<Block> out;
        const int last_row = rows < 0 ? image.height : rows;
        for (int y = 0; y < last_row; ++y) {
            for (int x = 0; x < image.width; ++x) {
                while (idle(rng)) {
                    m.ce = 0;
                    tick(out);
                }
                m.ce = 1;
                m.in_x = static_cast<std::uint16_t>(x);
                m.in_y = static_cast<std::uint16_t>(y);
                m.in_pixel = packed(image, x, y);
                tick(out);
            }
        }
        m.ce = 0;
        tick(out);  // the last block's output register
        return out;
    }

    void reset() { reset_stage(harness_); }

  private:
    void tick(std::vector<Block>& out) {
        harness_.tick();
        const Model& m = harness_.model();
        if (m.out_valid != 0) {
            out.push_back({signed_coord(m.out_x), signed_coord(m.out_y), m.out_pixel});
        }
    }

    sim::VerilatedHarness<Model> harness_;
};

template <typename Model>
void random_frames_equal_model(const char* name, int factor) {
    const int width = table::verilated(name).params.width;
    Downscaler<Model> rtl(name);
    auto rng = test::seeded_rng(static_cast<unsigned>(factor));
    std::uniform_int_distribution<int> any_width(factor, width);
    std::uniform_int_distribution<int> any_height(factor, 3 * factor + 5);
    for (int frame = 0; frame < 24; ++frame) {
        const Image image = test::random_image(frame == 0 ? width : any_width(rng),
                                               frame == 0 ? factor : any_height(rng), 3, rng);
        const double gap = frame % 3 == 0 ? 0.0 : 0.3;
        SCOPED_TRACE("frame " + std::to_string(frame) + ": " + std::to_string(image.width) + "x" +
                     std::to_string(image.height) + ", gap " + std::to_string(gap));
        EXPECT_EQ(rtl.stream(image, gap, rng), expected_blocks(image, factor));
    }
}

TEST(StereoDownscale, HalfEqualsModelOnRandomFrames) {
    random_frames_equal_model<Vstereo_downscale2>("Vstereo_downscale2", 2);
}

TEST(StereoDownscale, QuarterEqualsModelOnRandomFrames) {
    random_frames_equal_model<Vstereo_downscale4>("Vstereo_downscale4", 4);
}

// Saturated channels: the largest sums and the rounding of every block at 255 (and at 0, 1).
TEST(StereoDownscale, ExtremeValuesRoundHalfUp) {
    Downscaler<Vstereo_downscale4> rtl("Vstereo_downscale4");
    auto rng = test::seeded_rng(4);
    Image image(16, 8, 3);
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            for (int c = 0; c < 3; ++c) {
                // Block 0 all 255; block 1 one pixel 1 (mean 1/16: 0); block 2 eight 1s (8/16:
                // rounds up to 1); block 3 random.
                const int block = x / 4;
                const int in_block = (y % 4) * 4 + x % 4;
                image.at(x, y, c) =
                    static_cast<std::uint8_t>(block == 0   ? 255
                                              : block == 1 ? (in_block == 0 ? 1 : 0)
                                              : block == 2 ? (in_block < 8 ? 1 : 0)
                                                           : static_cast<int>(rng() & 255U));
            }
        }
    }
    const std::vector<Block> blocks = rtl.stream(image, 0.0, rng);
    ASSERT_EQ(blocks, expected_blocks(image, 4));
    EXPECT_EQ(blocks[0].pixel, 0xFFFFFFU);
    EXPECT_EQ(blocks[1].pixel, 0U);
    EXPECT_EQ(blocks[2].pixel, 0x010101U);
}

// A reset in the middle of a frame, then a whole frame: only the whole frame's blocks count, and
// nothing of the abandoned one leaks into them.
TEST(StereoDownscale, MidFrameResetThenWholeFrame) {
    Downscaler<Vstereo_downscale2> rtl("Vstereo_downscale2");
    auto rng = test::seeded_rng(22);
    const Image abandoned = test::random_image(40, 12, 3, rng);
    const Image next = test::random_image(38, 10, 3, rng);
    (void)rtl.stream(abandoned, 0.2, rng, 5);  // stops after 5 rows: inside the third block row
    rtl.reset();
    EXPECT_EQ(rtl.stream(next, 0.2, rng), expected_blocks(next, 2));
}

TEST(StereoDownscale, RealCropEqualsModel) {
    const auto crop = tsukuba_crop();
    if (!crop) {
        GTEST_SKIP() << "Middlebury tsukuba not found";
    }
    auto rng = test::seeded_rng(5);
    Downscaler<Vstereo_downscale2> half("Vstereo_downscale2");
    Downscaler<Vstereo_downscale4> quarter("Vstereo_downscale4");
    for (const Image* image : {&crop->left, &crop->right}) {
        EXPECT_EQ(half.stream(*image, 0.25, rng), expected_blocks(*image, 2));
        EXPECT_EQ(quarter.stream(*image, 0.25, rng), expected_blocks(*image, 4));
    }
}

}  // namespace
}  // namespace stereo::tb
