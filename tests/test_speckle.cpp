// The speckle filter (stereo/speckle.hpp): hand-made maps whose regions are known by
// construction, OpenCV's filterSpeckles as the independent reference on random maps, the
// registry's post-filter on every engine that has a validated output, and bad parameters.
#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <stdexcept>

#include <opencv2/calib3d.hpp>

#include "stereo/matcher.hpp"
#include "stereo/speckle.hpp"
#include "stereo_io/test_compare.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo {
namespace {

using test::same_validated;

// A width x height map, every pixel valid at `disparity` pixels, certainty 7.
ValidatedDisparity uniform_map(int width, int height, int disparity) {
    ValidatedDisparity map(width, height);
    for (std::size_t i = 0; i < map.fixed.size(); ++i) {
        map.fixed[i] = static_cast<std::int16_t>(disparity * fx::kSubpixelScale);
        map.reason[i] = fx::kReasonValid;
        map.certainty[i] = 7;
    }
    return map;
}

void set(ValidatedDisparity& map, int x, int y, int fixed) {
    map.fixed[map.index(x, y)] = static_cast<std::int16_t>(fixed);
}

TEST(Speckle, RemovesIslandsUpToTheSize) {
    // A 10 x 8 plane at 5 px with a 3-pixel L-shaped island at 20 px: a speckle of size 3.
    ValidatedDisparity map = uniform_map(10, 8, 5);
    for (const auto& [x, y] : {std::pair{4, 3}, {5, 3}, {5, 4}}) {
        set(map, x, y, 20 * fx::kSubpixelScale);
    }
    ValidatedDisparity kept = map;
    EXPECT_EQ(speckle::filter(kept, {2, 1}), 0);  // 3 pixels > 2: kept
    EXPECT_TRUE(same_validated(map, kept));
    ValidatedDisparity removed = map;
    EXPECT_EQ(speckle::filter(removed, {3, 1}), 3);
    for (int y = 0; y < 8; ++y) {
        for (int x = 0; x < 10; ++x) {
            const std::size_t i = map.index(x, y);
            const bool island = map.fixed[i] == 20 * fx::kSubpixelScale;
            EXPECT_EQ(removed.reason[i], island ? fx::kReasonSpeckle : fx::kReasonValid);
            EXPECT_EQ(removed.fixed[i], island ? 0 : map.fixed[i]);
            EXPECT_EQ(removed.certainty[i], 7);  // the certainty stays
        }
    }
}

TEST(Speckle, RangeDecidesWhatIsConnected) {
    // One row of 6 pixels: 3 at 10 px, then 3 at 10 px + step. Size 3: each half is a speckle
    // unless the step connects them into one region of 6.
    for (const int step : {15, 16, 17, 32, 33}) {
        ValidatedDisparity map = uniform_map(6, 1, 10);
        for (int x = 3; x < 6; ++x) {
            set(map, x, 0, 10 * fx::kSubpixelScale + step);
        }
        for (const int range : {1, 2}) {
            ValidatedDisparity filtered = map;
            const bool connected = step <= range * fx::kSubpixelScale;
            EXPECT_EQ(speckle::filter(filtered, {3, range}), connected ? 0 : 6)
                << "step " << step << " range " << range;
        }
    }
}

TEST(Speckle, InvalidPixelsSeparateRegionsAndStayAsTheyAre) {
    // A column of left-right-invalid pixels cuts a 7 x 3 plane into 3 x 3 and 3 x 3.
    ValidatedDisparity map = uniform_map(7, 3, 4);
    for (int y = 0; y < 3; ++y) {
        map.reason[map.index(3, y)] = fx::kReasonLeftRight;
        set(map, 3, y, 0);
    }
    ValidatedDisparity filtered = map;
    EXPECT_EQ(speckle::filter(filtered, {9, 1}), 18);
    for (int y = 0; y < 3; ++y) {
        EXPECT_EQ(filtered.reason[map.index(3, y)], fx::kReasonLeftRight);
        EXPECT_EQ(filtered.reason[map.index(0, y)], fx::kReasonSpeckle);
    }
    filtered = map;
    EXPECT_EQ(speckle::filter(filtered, {8, 1}), 0);
    // Diagonal neighbours do not connect (4-connectivity, as OpenCV's filter).
    ValidatedDisparity diagonal(2, 2);
    diagonal.reason = {fx::kReasonValid, fx::kReasonBorder, fx::kReasonBorder, fx::kReasonValid};
    EXPECT_EQ(speckle::filter(diagonal, {1, 1}), 2);
}

TEST(Speckle, OffLeavesTheMapAlone) {
    ValidatedDisparity map = uniform_map(4, 4, 3);
    set(map, 1, 1, 200);
    ValidatedDisparity filtered = map;
    EXPECT_EQ(speckle::filter(filtered, {}), 0);
    EXPECT_TRUE(same_validated(map, filtered));
}

// OpenCV's filterSpeckles on the same map: disparities x 16 in a CV_16S image, invalid pixels as
// its `newVal` (which it skips), size and range in the same units.
ValidatedDisparity opencv_filtered(const ValidatedDisparity& map, const speckle::Params& params) {
    constexpr std::int16_t kInvalid = std::numeric_limits<std::int16_t>::min();
    cv::Mat image(map.height, map.width, CV_16SC1);
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            const std::size_t i = map.index(x, y);
            image.at<std::int16_t>(y, x) = map.valid(i) ? map.fixed[i] : kInvalid;
        }
    }
    cv::filterSpeckles(image, kInvalid, params.max_size, params.range * fx::kSubpixelScale);
    ValidatedDisparity out = map;
    for (int y = 0; y < map.height; ++y) {
        for (int x = 0; x < map.width; ++x) {
            const std::size_t i = map.index(x, y);
            if (map.valid(i) && image.at<std::int16_t>(y, x) == kInvalid) {
                out.reason[i] = fx::kReasonSpeckle;
                out.fixed[i] = 0;
            }
        }
    }
    return out;
}

TEST(Speckle, EqualsOpenCVOnRandomMaps) {
    // Blocky random maps (so regions of every size occur) with sub-pixel jitter and invalid
    // pixels of every reason, at several sizes and ranges.
    std::mt19937 rng(16);
    int removed_total = 0;
    for (int trial = 0; trial < 12; ++trial) {
        const int width = 17 + trial * 5;
        const int height = 13 + trial * 3;
        ValidatedDisparity map(width, height);
        std::uniform_int_distribution<int> block_value(-8, 40);
        std::uniform_int_distribution<int> jitter(-20, 20);
        std::uniform_int_distribution<int> percent(0, 99);
        const int block = 1 + trial % 4;
        std::vector<int> blocks(
            static_cast<std::size_t>((width / block + 1) * (height / block + 1)));
        for (int& b : blocks) {
            b = block_value(rng) * fx::kSubpixelScale;
        }
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const std::size_t i = map.index(x, y);
                const int roll = percent(rng);
                if (roll < 15) {
                    map.reason[i] = static_cast<std::uint8_t>(1 + roll % 3);
                    continue;
                }
                map.reason[i] = fx::kReasonValid;
                map.fixed[i] =
                    static_cast<std::int16_t>(blocks[static_cast<std::size_t>(
                                                  (y / block) * (width / block + 1) + x / block)] +
                                              jitter(rng));
            }
        }
        for (const speckle::Params params :
             {speckle::Params{1, 0}, {4, 1}, {25, 1}, {25, 2}, {100, 3}, {100000, 1}}) {
            ValidatedDisparity ours = map;
            removed_total += speckle::filter(ours, params);
            EXPECT_TRUE(same_validated(opencv_filtered(map, params), ours))
                << "trial " << trial << " size " << params.max_size << " range " << params.range;
        }
    }
    EXPECT_GT(removed_total, 1000);  // speckles of every size were there to find
}

TEST(Speckle, RejectsImpossibleParameters) {
    ValidatedDisparity map = uniform_map(3, 3, 1);
    EXPECT_THROW(speckle::filter(map, {-1, 1}), std::invalid_argument);
    EXPECT_THROW(speckle::filter(map, {speckle::kMaxSize + 1, 1}), std::invalid_argument);
    EXPECT_THROW(speckle::filter(map, {10, -1}), std::invalid_argument);
    EXPECT_THROW(speckle::filter(map, {10, speckle::kMaxRange + 1}), std::invalid_argument);
    MatcherRegistry registry;
    register_model_matchers(registry);
    MatchConfig config;
    config.speckle = {-5, 1};
    EXPECT_THROW(registry.create("pipeline", "model", config), std::invalid_argument);
}

TEST(Speckle, RegistryFiltersEveryValidatedEngine) {
    // Two unrelated random images (a map full of speckles): the registry's output with the filter
    // on equals the filter applied by hand to its output with the filter off, for the model, the
    // naive reference and ASW.
    std::mt19937 rng = test::seeded_rng(22);
    const Image left = test::random_image(48, 32, 3, rng);
    const Image right = test::random_image(48, 32, 3, rng);
    MatcherRegistry registry;
    register_model_matchers(registry);
    MatchConfig config;
    config.pipeline.ndisp = 8;
    config.pipeline.window = 5;
    config.pipeline.validation = ValidationParams::all_on();
    config.asw.diameter = 7;
    config.asw.threads = 1;
    for (const auto& [method, engine] :
         {std::pair{"pipeline", "model"}, {"pipeline", "naive"}, {"asw", "model"}}) {
        const MatchResult plain = registry.create(method, engine, config)->compute(left, right);
        MatchConfig filtered_config = config;
        filtered_config.speckle = {20, 1};
        const MatchResult filtered =
            registry.create(method, engine, filtered_config)->compute(left, right);
        ValidatedDisparity expected = plain.validated;
        const int removed = speckle::filter(expected, filtered_config.speckle);
        EXPECT_TRUE(same_validated(expected, filtered.validated)) << method << " " << engine;
        EXPECT_GT(removed, 0) << method << " " << engine;  // the case exercises the filter
        EXPECT_EQ(filtered.count("speckle"), removed);
        EXPECT_EQ(filtered.disparity.disparity, to_label_map(expected).disparity);
    }
}

}  // namespace
}  // namespace stereo
