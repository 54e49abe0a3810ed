// Row-band parallel front ends (robot/bands.hpp) against the single-threaded golden model: equal
// bit for bit on random images of odd sizes, grey and colour, and on real pairs.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>
#include <string>

#include "stereo/edge_frontend.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/test_support.hpp"
#include "stereo_robot/bands.hpp"

namespace stereo::robot {
namespace {

namespace fs = std::filesystem;

// A random pair whose right image is the left shifted by a random per-row disparity plus noise,
// so that matching has something to find.
std::pair<Image, Image> random_pair(int width, int height, int channels, std::mt19937& rng) {
    std::uniform_int_distribution<int> grey(0, 255);
    std::uniform_int_distribution<int> shift(0, 12);
    std::uniform_int_distribution<int> noise(-6, 6);
    Image left(width, height, channels);
    Image right(width, height, channels);
    for (auto& p : left.pixels) {
        p = static_cast<std::uint8_t>(grey(rng));
    }
    for (int y = 0; y < height; ++y) {
        const int d = shift(rng);
        for (int x = 0; x < width; ++x) {
            for (int c = 0; c < channels; ++c) {
                const int v = left.at(std::min(width - 1, x + d), y, c) + noise(rng);
                right.at(x, y, c) = static_cast<std::uint8_t>(std::clamp(v, 0, 255));
            }
        }
    }
    return {left, right};
}

TEST(Bands, EdgeFrontendEqualsTheSingleThreadedModel) {
    auto rng = test::seeded_rng(3);
    MatchParams params;
    params.ndisp = 16;
    for (const auto& [w, h, c] : {std::tuple{97, 61, 1}, std::tuple{64, 131, 3},
                                  std::tuple{41, 40, 1}, std::tuple{120, 203, 1}}) {
        const auto [left, right] = random_pair(w, h, c, rng);
        const DisparityMap one = edge_frontend::match(left, right, params);
        for (const int threads : {2, 3, 5, 16}) {
            EXPECT_EQ(edge_match_bands(left, right, params, {}, threads), one)
                << w << "x" << h << "x" << c << " threads " << threads;
        }
    }
    // Another window and LoG size change the reach; still equal.
    params.window = 7;
    edge_frontend::EdgeParams edges;
    edges.log_window = 9;
    edges.log_sigma = 1.5;
    const auto [left, right] = random_pair(90, 150, 1, rng);
    EXPECT_EQ(edge_match_bands(left, right, params, edges, 4),
              edge_frontend::match(left, right, params, edges));
}

// The SLAM front end runs on the fast engine: equal to the registry's model engine ("sparse",
// "model"), disparities and reason counts, on every thread count.
TEST(Bands, SparseFrontendEqualsTheSingleThreadedModel) {
    auto rng = test::seeded_rng(4);
    slam::FrontendParams params;
    params.ndisp = 16;
    for (const std::string cost : {"ad", "census"}) {
        params.cost = cost;
        for (const auto& [w, h] : {std::pair{97, 61}, std::pair{64, 131}, std::pair{120, 203}}) {
            const auto [left, right] = random_pair(w, h, 1, rng);
            slam::ValidationCounts model_counts;
            const auto model = slam::sparse_disparity_model(left, right, params, &model_counts);
            ASSERT_GT(model_counts.valid, 0U);
            for (const int threads : {1, 2, 3, 7}) {
                slam::ValidationCounts counts;
                const auto fast = slam::sparse_disparity(left, right, params, &counts, threads);
                ASSERT_EQ(fast.disparity.size(), model.disparity.size());
                EXPECT_TRUE(fast.disparity == model.disparity)
                    << cost << " " << w << "x" << h << " " << threads;
                EXPECT_EQ(counts.valid, model_counts.valid) << cost << " " << threads;
                EXPECT_EQ(counts.uncertain, model_counts.uncertain) << cost << " " << threads;
                EXPECT_EQ(counts.inconsistent, model_counts.inconsistent) << cost << " " << threads;
                EXPECT_TRUE(sparse_disparity_bands(left, right, params, threads).disparity ==
                            model.disparity);
            }
        }
    }
}

TEST(Bands, KittiFrameEqualsTheSingleThreadedModel) {
    const fs::path dir = io::data_dir() / "sequence" / "kitti_sequence_2";
    if (!fs::is_directory(dir)) {
        GTEST_SKIP() << "no KITTI data at " << dir;
    }
    const io::ImagePair pair =
        io::load_pair(dir / "image_l" / "000010.png", dir / "image_r" / "000010.png");
    const MatchParams params;
    EXPECT_EQ(edge_match_bands(pair.left, pair.right, params, {}, 2),
              edge_frontend::match(pair.left, pair.right, params));
    slam::FrontendParams sparse;
    EXPECT_TRUE(sparse_disparity_bands(pair.left, pair.right, sparse, 2).disparity ==
                slam::sparse_disparity_model(pair.left, pair.right, sparse).disparity);
}

}  // namespace
}  // namespace stereo::robot
