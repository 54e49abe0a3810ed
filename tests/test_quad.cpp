// Quad-camera matching (issue 22): each pair geometry of the model against its naive reference
// and against the volume form, known vertical and diagonal shifts recovered exactly, the fusion
// on hand-made maps and against its naive reference, the threaded quad against the sequential
// one, and the errors for views that do not fit.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include <cmath>
#include <cstdio>

#include "stereo/quad.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/test_compare.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo::quad {
namespace {

using test::same_validated;

// Reference (x, y) sees partner (x - d sx, y - d sy): the partner is the crop shifted by +d step.
// Crops of one random image make a pair whose true disparity is d everywhere, with no clamped or
// invented pixels.
std::pair<Image, Image> shifted_views(Pair pair, int d, int width, int height, int channels,
                                      std::mt19937& rng) {
    constexpr int kMargin = 16;
    const Image big = test::random_image(width + 2 * kMargin, height + 2 * kMargin, channels, rng);
    const Step s = step(pair);
    return {io::crop(big, kMargin, kMargin, width, height),
            io::crop(big, kMargin + d * s.x, kMargin + d * s.y, width, height)};
}

MatchParams small_params(int ndisp, int min_disp, bool validation) {
    MatchParams params;
    params.ndisp = ndisp;
    params.window = 5;
    params.sigma = 1.5;
    params.min_disp = min_disp;
    if (validation) {
        params.validation = ValidationParams::all_on();
    }
    return params;
}

TEST(QuadPairs, ModelEqualsNaiveAndVolumeForm) {
    auto rng = test::seeded_rng(22);
    for (const std::string_view cost : kPairCosts) {
        for (const Pair pair : kPairs) {
            for (const int channels : {1, 3}) {
                if (cost == "lcdm" && channels == 1) {
                    continue;  // colour only (QuadErrors)
                }
                for (const bool validation : {false, true}) {
                    // Odd sizes, a signed range, noise so that the CA rules and stage 6 all act.
                    const auto [reference, partner] =
                        shifted_views(pair, -2, 31, 27, channels, rng);
                    Image noisy = partner;
                    std::uniform_int_distribution<int> noise(-12, 12);
                    for (auto& v : noisy.pixels) {
                        v = static_cast<std::uint8_t>(std::clamp(v + noise(rng), 0, 255));
                    }
                    MatchParams params = small_params(7, -4, validation);
                    params.cost = cost;
                    const auto model = match_pair(pair, reference, noisy, params);
                    SCOPED_TRACE(std::string(cost) + " " + std::string(name(pair)) + " channels " +
                                 std::to_string(channels) + (validation ? " validated" : " plain"));
                    EXPECT_TRUE(
                        same_validated(naive::match_pair(pair, reference, noisy, params), model));
                    EXPECT_TRUE(
                        same_validated(match_pair_volume(pair, reference, noisy, params), model));
                }
            }
        }
    }
}

TEST(QuadPairs, KnownShiftsAreRecoveredExactly) {
    auto rng = test::seeded_rng(23);
    for (const std::string_view cost : kPairCosts) {
        for (const Pair pair : {Pair::vertical, Pair::diagonal, Pair::horizontal}) {
            for (const int d : {-3, 0, 4}) {
                const auto [reference, partner] = shifted_views(pair, d, 40, 36, 3, rng);
                MatchParams params = small_params(11, -5, false);
                params.cost = cost;
                const auto result = match_pair(pair, reference, partner, params);
                const int reach = invalid_border(params).reach;
                const Step s = step(pair);
                int checked = 0;
                for (int y = reach; y < reference.height - reach; ++y) {
                    for (int x = reach; x < reference.width - reach; ++x) {
                        const int xs = x - d * s.x;
                        const int ys = y - d * s.y;
                        if (xs < reach || ys < reach || xs >= reference.width - reach ||
                            ys >= reference.height - reach) {
                            continue;
                        }
                        const auto i = result.index(x, y);
                        ASSERT_TRUE(result.valid(i))
                            << cost << " " << name(pair) << " d " << d << " at " << x << "," << y;
                        ASSERT_EQ(result.fixed[i], 16 * d)
                            << cost << " " << name(pair) << " at " << x << "," << y;
                        ++checked;
                    }
                }
                EXPECT_GT(checked, 100);
            }
        }
    }
}

ValidatedDisparity map_of(std::vector<std::int16_t> fixed, std::vector<std::uint8_t> reason,
                          std::vector<std::uint8_t> certainty) {
    ValidatedDisparity map(static_cast<int>(fixed.size()), 1);
    map.fixed = std::move(fixed);
    map.reason = std::move(reason);
    map.certainty = std::move(certainty);
    return map;
}

TEST(QuadFusion, PicksTheMostCertainValidPair) {
    // Pixel 0: vertical most certain. 1: diagonal most certain. 2: a tie of horizontal and
    // diagonal goes to horizontal. 3: the most certain (vertical) is invalid, so diagonal.
    // 4: nothing valid. 5: a tie of vertical and diagonal goes to vertical.
    const auto h = map_of({16, 32, 48, 64, 0, 80}, {0, 0, 0, 1, 1, 0}, {10, 50, 90, 200, 7, 3});
    const auto v = map_of({17, 33, 49, 65, 0, 81}, {0, 0, 0, 3, 2, 0}, {99, 60, 20, 250, 9, 40});
    const auto d = map_of({18, 34, 50, 66, 0, 82}, {0, 0, 0, 0, 1, 0}, {20, 61, 90, 5, 9, 40});
    for (const bool use_naive : {false, true}) {
        const QuadResult r = use_naive ? naive::fuse({h, v, d}) : fuse({h, v, d});
        EXPECT_EQ(r.fused.fixed, (std::vector<std::int16_t>{17, 34, 48, 66, 0, 81}));
        EXPECT_EQ(r.source, (std::vector<std::uint8_t>{2, 3, 1, 3, 0, 2}));
        EXPECT_EQ(r.fused.certainty, (std::vector<std::uint8_t>{99, 61, 90, 5, 0, 40}));
        EXPECT_EQ(r.fused.reason, (std::vector<std::uint8_t>{0, 0, 0, 0, 1, 0}));
    }
}

TEST(QuadFusion, ModelEqualsNaiveOnRandomMaps) {
    auto rng = test::seeded_rng(24);
    std::uniform_int_distribution<int> value(0, 255);
    std::uniform_int_distribution<int> reason(0, 3);
    std::array<ValidatedDisparity, 3> maps;
    for (auto& map : maps) {
        map = ValidatedDisparity(53, 17);
        for (std::size_t i = 0; i < map.fixed.size(); ++i) {
            map.reason[i] = static_cast<std::uint8_t>(reason(rng) == 0 ? 1 : 0);
            map.certainty[i] = static_cast<std::uint8_t>(value(rng) / 16);  // many ties
            map.fixed[i] = static_cast<std::int16_t>(map.reason[i] == 0 ? value(rng) - 128 : 0);
        }
    }
    const QuadResult model = fuse(maps);
    const QuadResult reference = naive::fuse(maps);
    EXPECT_TRUE(same_validated(reference.fused, model.fused));
    EXPECT_EQ(reference.source, model.source);
}

TEST(QuadFusion, ByCostPicksTheSmallestWinnerCost) {
    // The certainties point the other way on purpose. Pixel 0: vertical cheapest. 1: diagonal
    // cheapest. 2: a cost tie of horizontal and diagonal goes to horizontal. 3: the cheapest
    // (vertical) is invalid, so diagonal. 4: nothing valid.
    const auto h = map_of({16, 32, 48, 64, 0}, {0, 0, 0, 1, 1}, {250, 250, 5, 250, 7});
    const auto v = map_of({17, 33, 49, 65, 0}, {0, 0, 0, 3, 2}, {3, 250, 250, 250, 9});
    const auto d = map_of({18, 34, 50, 66, 0}, {0, 0, 0, 0, 1}, {250, 4, 250, 6, 9});
    const std::array<PairMatch, 3> pairs = {PairMatch{h, {900, 500, 300, 10, 0}},
                                            PairMatch{v, {100, 400, 301, 5, 0}},
                                            PairMatch{d, {800, 399, 300, 12240, 0}}};
    for (const bool use_naive : {false, true}) {
        const QuadResult r = use_naive ? naive::fuse_by_cost(pairs) : fuse_by_cost(pairs);
        EXPECT_EQ(r.fused.fixed, (std::vector<std::int16_t>{17, 34, 48, 66, 0}));
        EXPECT_EQ(r.source, (std::vector<std::uint8_t>{2, 3, 1, 3, 0}));
        EXPECT_EQ(r.fused.certainty, (std::vector<std::uint8_t>{3, 4, 5, 6, 0}));
        EXPECT_EQ(r.fused.reason, (std::vector<std::uint8_t>{0, 0, 0, 0, 1}));
    }
    std::array<PairMatch, 3> short_costs = pairs;
    short_costs[1].cost.pop_back();
    EXPECT_THROW((void)fuse_by_cost(short_costs), std::invalid_argument);
    EXPECT_THROW((void)naive::fuse_by_cost(short_costs), std::invalid_argument);
}

TEST(QuadFusion, KeysByName) {
    EXPECT_EQ(fusion_key("certainty"), FusionKey::certainty);
    EXPECT_EQ(fusion_key("cost"), FusionKey::cost);
    EXPECT_EQ(name(FusionKey::cost), "cost");
    EXPECT_THROW((void)fusion_key("ratio"), std::invalid_argument);
}

TEST(QuadPairs, WinnerCostsEqualNaive) {
    // C1 of every pixel, the model (streaming for the horizontal and vertical pairs, the volume
    // for the diagonal) against the naive stages, on a non-square frame (the vertical transpose).
    auto rng = test::seeded_rng(27);
    for (const Pair pair : kPairs) {
        const auto [reference, partner] = shifted_views(pair, 1, 29, 23, 3, rng);
        const MatchParams params = small_params(6, -2, true);
        const PairMatch model = match_pair_with_cost(pair, reference, partner, params);
        const PairMatch slow = naive::match_pair_with_cost(pair, reference, partner, params);
        SCOPED_TRACE(std::string(name(pair)));
        EXPECT_EQ(model.cost, slow.cost);
        EXPECT_EQ(model.cost.size(), model.map.fixed.size());
        EXPECT_TRUE(same_validated(slow.map, model.map));
        EXPECT_TRUE(same_validated(match_pair(pair, reference, partner, params), model.map));
    }
}

TEST(QuadMatch, ThreadedModelEqualsSequentialAndNaive) {
    auto rng = test::seeded_rng(25);
    const Image reference = test::random_image(33, 29, 3, rng);
    const Image right = test::random_image(33, 29, 3, rng);
    const Image below = test::random_image(33, 29, 3, rng);
    const Image diagonal = test::random_image(33, 29, 3, rng);
    const QuadViews views{reference, right, below, diagonal};
    const MatchParams params = small_params(6, -2, true);
    const QuadResult threaded = match_quad(views, params, true);
    const QuadResult sequential = match_quad(views, params, false);
    const QuadResult slow = naive::match_quad(views, params);
    EXPECT_TRUE(same_validated(sequential.fused, threaded.fused));
    EXPECT_TRUE(same_validated(slow.fused, threaded.fused));
    EXPECT_EQ(slow.source, threaded.source);
    for (std::size_t p = 0; p < 3; ++p) {
        EXPECT_TRUE(same_validated(slow.pairs[p], threaded.pairs[p]));
    }
    // Fused by cost, with and without stage 6's checks: the same three pairs, another choice.
    for (const bool validation : {true, false}) {
        const MatchParams p6 = small_params(6, -2, validation);
        const QuadResult by_certainty = match_quad(views, p6, true);
        const QuadResult by_cost = match_quad(views, p6, true, FusionKey::cost);
        const QuadResult by_cost_sequential = match_quad(views, p6, false, FusionKey::cost);
        const QuadResult by_cost_slow = naive::match_quad(views, p6, FusionKey::cost);
        EXPECT_TRUE(same_validated(by_cost_slow.fused, by_cost.fused));
        EXPECT_TRUE(same_validated(by_cost_sequential.fused, by_cost.fused));
        EXPECT_EQ(by_cost_slow.source, by_cost.source);
        for (std::size_t p = 0; p < 3; ++p) {
            EXPECT_TRUE(same_validated(by_certainty.pairs[p], by_cost.pairs[p]));
        }
        if (!validation) {  // dense random pairs: the two keys disagree somewhere
            EXPECT_NE(by_cost.source, by_certainty.source);
        }
    }
}

TEST(QuadMatch, ViewsThatDoNotFitAreRefused) {
    auto rng = test::seeded_rng(26);
    const Image reference = test::random_image(40, 30, 3, rng);
    const Image smaller = test::random_image(40, 29, 3, rng);
    const Image grey = test::random_image(40, 30, 1, rng);
    const MatchParams params = small_params(8, 0, false);
    EXPECT_THROW(match_quad({reference, reference, smaller, reference}, params),
                 std::invalid_argument);
    EXPECT_THROW(match_quad({reference, reference, reference, grey}, params),
                 std::invalid_argument);
    // A range that leaves the image along the vertical axis only (height 30).
    EXPECT_THROW(
        match_quad({reference, reference, reference, reference}, small_params(4, 30, false)),
        std::invalid_argument);
    EXPECT_NO_THROW(validate_pair(Pair::horizontal, small_params(4, 30, false), 40, 30));
    MatchParams census = params;
    census.cost = "census";
    EXPECT_NO_THROW(validate_pair(Pair::vertical, census, 40, 30));
    MatchParams zncc = params;
    zncc.cost = "zncc";
    EXPECT_NO_THROW(validate_pair(Pair::horizontal, zncc, 40, 30));
    EXPECT_THROW(validate_pair(Pair::vertical, zncc, 40, 30), std::invalid_argument);
    EXPECT_THROW(validate_pair(Pair::diagonal, zncc, 40, 30), std::invalid_argument);
    // LCDM compares colours: grey views fail with a clear error, in the model and the reference.
    MatchParams lcdm = params;
    lcdm.cost = "lcdm";
    EXPECT_THROW(match_pair(Pair::diagonal, grey, grey, lcdm), std::invalid_argument);
    EXPECT_THROW(naive::match_pair(Pair::diagonal, grey, grey, lcdm), std::invalid_argument);
}

TEST(QuadLightField, EveryPairFollowsTheGridGeometry) {
    // The sign convention of each pair on real data (data/README.md: d = n * g, the partner n
    // views right / down / both): on a 96 x 96 crop of antinous at n = 2, most interior pixels
    // of each pair lie within 1 px of the ground truth. With a wrong sign or axis almost none do.
    const auto dir = io::data_dir() / "lightfield" / "antinous";
    if (!std::filesystem::exists(dir / "gt_disp_lowres.pfm")) {
        GTEST_SKIP() << "antinous not found under " << dir;
    }
    constexpr int kN = 2;
    constexpr int kX0 = 200;
    constexpr int kY0 = 150;
    constexpr int kSide = 96;
    const auto view = [&](int index) {
        char name[32];
        std::snprintf(name, sizeof name, "input_Cam%03d.png", index);
        return io::crop(io::load_image(dir / name), kX0, kY0, kSide, kSide);
    };
    const cv::Mat g =
        io::load_disparity_file(dir / "gt_disp_lowres.pfm", io::DisparityEncoding::pfm, 1.0);
    const Image reference = view(40);
    const std::array<Image, 3> partners = {view(40 + kN), view(40 + 9 * kN), view(40 + 10 * kN)};
    MatchParams params;
    params.ndisp = 16;
    params.min_disp = -8;
    params.window = 13;
    for (const Pair pair : kPairs) {
        const auto result =
            match_pair(pair, reference, partners[static_cast<std::size_t>(pair)], params);
        int close = 0;
        int scored = 0;
        for (int y = 24; y < kSide - 24; ++y) {
            for (int x = 24; x < kSide - 24; ++x) {
                const auto i = result.index(x, y);
                ++scored;
                const double truth = kN * g.at<float>(kY0 + y, kX0 + x);
                close += result.valid(i) && std::abs(result.disparity(i) - truth) <= 1.0 ? 1 : 0;
            }
        }
        EXPECT_GT(close, scored * 3 / 4) << name(pair) << ": " << close << " of " << scored;
    }
}

}  // namespace
}  // namespace stereo::quad
