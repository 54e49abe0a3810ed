// The matcher interface: the registry, every registered engine against the model, the plane
// scheduler's census plug-in against its naive reference and a hand-computed case.
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "stereo/hierarchical.hpp"
#include "stereo/hierarchical_reference.hpp"
#include "stereo/matcher.hpp"
#include "stereo/reference.hpp"
#include "stereo/stages.hpp"
#include "stereo/stages/census.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo {
namespace {

MatcherRegistry model_registry() {
    MatcherRegistry registry;
    register_model_matchers(registry);
    return registry;
}

// ---- census: plug-in vs naive reference, and by hand ------------------------------------

TEST(Census, CostVolumeEqualsNaive) {
    std::mt19937 rng(test::test_seed());
    for (const int channels : {1, 3}) {
        const auto [left, right] = test::shifted_pair(37, 23, channels, 4, 6, rng);
        const auto census = make_census_cost();
        EXPECT_EQ(cost_volume(*census, left, right, 9), census::naive::cost(left, right, 9))
            << channels << " channel(s)";
    }
}

TEST(Census, MatchEqualsNaiveAndFindsTheShift) {
    std::mt19937 rng(test::test_seed());
    const auto [left, right] = test::shifted_pair(48, 32, 3, 5, 4, rng);
    MatchParams params{12, 5, 1.5, true, "census"};
    const DisparityMap model = match(left, right, params);
    EXPECT_EQ(model, naive::match(left, right, params));
    // The true disparity wins wherever the pixel is valid and inside the shifted region.
    int correct = 0;
    int valid = 0;
    for (int y = 0; y < model.height; ++y) {
        for (int x = 0; x < model.width - 5; ++x) {
            if (model.valid[model.index(x, y)] != 0) {
                ++valid;
                correct += model.disparity[model.index(x, y)] == 5 ? 1 : 0;
            }
        }
    }
    ASSERT_GT(valid, 0);
    EXPECT_GT(correct, valid * 9 / 10);
}

TEST(Census, HandComputedCode) {
    // A 5x5 grey image: centre 100, the pixel to its right 200, all others 50. Raster order of
    // the 24 neighbours puts "right of centre" at bit index 12 (counting from the first
    // neighbour), i.e. the 12th bit from the top of the 24-bit code: every neighbour but that
    // one is darker, so the code is 0xFFFFFF with bit (23 - 12) = 11 cleared.
    Image image(5, 5, 1);
    for (auto& p : image.pixels) {
        p = 50;
    }
    image.at(2, 2, 0) = 100;
    image.at(3, 2, 0) = 200;
    const auto codes = census::transform(image);
    EXPECT_EQ(codes[2 * 5 + 2], 0xFFFFFFU & ~(1U << 11));
    // A corner pixel of a flat image: no neighbour is darker.
    EXPECT_EQ(codes[0], 0U);
    // Cost of the centre against a flat image's centre (code 0): 23 differing bits.
    Image flat(5, 5, 1);
    for (auto& p : flat.pixels) {
        p = 50;
    }
    const Dsi dsi = cost_volume(*make_census_cost(), image, flat, 1);
    EXPECT_EQ(dsi.at(2, 2, 0), 23 * census::kWeight);
}

// The hierarchical 2-D search with the census cost (codes of each level's image) equals its naive
// reference (codes rebuilt bit by bit for every comparison), on a colour and a grey pair shifted
// by 5 pixels; and it finds the shift.
TEST(Census, HierarchicalSearchEqualsNaive) {
    std::mt19937 rng(test::test_seed() + 7);
    hierarchical::Params params;
    params.ndisp = 16;
    params.vrange = 8;
    params.cost = "census";
    for (const int channels : {3, 1}) {
        const auto [left, right] = test::shifted_pair(72, 56, channels, 5, 3, rng);
        const auto model = hierarchical::match(left, right, params);
        const auto reference = hierarchical::naive::match(left, right, params);
        EXPECT_EQ(reference.disparity, model.disparity) << channels << " channels";
        EXPECT_EQ(reference.vertical, model.vertical) << channels << " channels";
        int found = 0;
        for (int y = 16; y < 40; ++y) {
            for (int x = 24; x < 56; ++x) {
                const auto p = static_cast<std::size_t>(y) * model.disparity.width + x;
                found += model.disparity.valid[p] && model.disparity.disparity[p] == 5 ? 1 : 0;
            }
        }
        EXPECT_GT(found, 24 * 32 * 8 / 10) << channels << " channels";  // measured: 90 %
    }
}

TEST(Census, UnknownCostIsRejected) {
    EXPECT_THROW(make_cost("sad"), std::invalid_argument);
    MatchParams params;
    params.cost = "sad";
    EXPECT_THROW(validate(params, 100, 100), std::invalid_argument);
}

// ---- the registry -----------------------------------------------------------------------

TEST(Registry, UnknownMethodOrEngineIsAUsageError) {
    const MatcherRegistry registry = model_registry();
    EXPECT_THROW(registry.create("nope", "model", {}), std::invalid_argument);
    EXPECT_THROW(registry.create("pipeline", "nope", {}), std::invalid_argument);
    EXPECT_THROW(registry.create("edges", "float", {}), std::invalid_argument);
}

TEST(Registry, DuplicateRegistrationIsRefused) {
    MatcherRegistry registry = model_registry();
    EXPECT_THROW(register_model_matchers(registry), std::logic_error);
}

TEST(Registry, EveryEngineOfAMethodAgreesWithTheModel) {
    // Engines that are bit-exact with the model must give the same map; float and full-search
    // compute something else on purpose and only have to run.
    std::mt19937 rng(test::test_seed());
    const auto [left, right] = test::shifted_pair(64, 48, 3, 3, 4, rng);
    const MatcherRegistry registry = model_registry();
    MatchConfig config;
    config.pipeline = {8, 5, 1.5, true};
    config.asw.diameter = 9;  // the default circle (55) does not fit a 64 x 48 pair
    for (const auto& entry : registry.entries()) {
        const auto matcher = registry.create(entry.method, entry.engine, config);
        matcher->validate(left.width, left.height);
        const MatchResult result = matcher->compute(left, right);
        ASSERT_EQ(result.disparity.width, left.width) << entry.method << "/" << entry.engine;
        if (entry.engine == "naive") {
            const MatchResult model =
                registry.create(entry.method, "model", config)->compute(left, right);
            EXPECT_EQ(result.disparity, model.disparity) << entry.method;
            EXPECT_EQ(result.vertical, model.vertical) << entry.method;
        }
    }
}

TEST(Registry, ValidateRejectsWhatComputeWouldReject) {
    const MatcherRegistry registry = model_registry();
    MatchConfig config;
    config.pipeline.ndisp = 64;
    for (const auto& entry : registry.entries()) {
        const auto matcher = registry.create(entry.method, entry.engine, config);
        EXPECT_THROW(matcher->validate(32, 32), std::invalid_argument)
            << entry.method << "/" << entry.engine;
    }
}

}  // namespace
}  // namespace stereo
