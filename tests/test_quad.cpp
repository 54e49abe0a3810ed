// Quad-camera matching (issue 22): each pair geometry of the model against its naive reference
// and against the volume form, known vertical and diagonal shifts recovered exactly, the fusion
// on hand-made maps and against its naive reference, the threaded quad against the sequential
// one, and the errors for views that do not fit.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <stdexcept>
#include <string>

#include "stage6_counts.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/quad.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/disparity_files.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/test_compare.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo::quad {
namespace {

using test::same_validated;
using test::stage6_counts;
using test::Stage6Counts;

// docs/quad.md's geometry table, written out here rather than read from quad::step (which the
// model and the naive reference share): reference (x, y) sees partner (x - d sx, y - d sy).
Step documented_step(Pair pair) {
    constexpr std::array<std::pair<Pair, Step>, 3> kTable{
        {{Pair::horizontal, {1, 0}}, {Pair::vertical, {0, 1}}, {Pair::diagonal, {1, 1}}}};
    for (const auto& [listed, listed_step] : kTable) {
        if (listed == pair) {
            return listed_step;
        }
    }
    ADD_FAILURE() << "no documented step for pair " << static_cast<int>(pair);
    return {};
}

// Reference (x, y) sees partner (x - d sx, y - d sy): the partner is the crop shifted by +d step.
// Crops of one random image make a pair whose true disparity is d everywhere, with no clamped or
// invented pixels.
std::pair<Image, Image> shifted_views(Pair pair, int d, int width, int height, int channels,
                                      std::mt19937& rng) {
    constexpr int kMargin = 16;
    const Image big = test::random_image(width + 2 * kMargin, height + 2 * kMargin, channels, rng);
    const Step s = documented_step(pair);
    return {io::crop(big, kMargin, kMargin, width, height),
            io::crop(big, kMargin + d * s.x, kMargin + d * s.y, width, height)};
}

// A scene seen by the reference camera (the centre of `big`, kSceneMargin from each edge) and by
// a partner along `pair` (documented_step): a background plane whose disparity grows from `far`
// at the top left to `far + slant` at the bottom right (the partner samples it between pixels,
// linearly interpolated along the step), and a box in the middle in front of it at the integer
// disparity `near`; plus noise. Beside the box the background is hidden in the partner (stage
// 6's left-right check rejects it there), the background the box hides in the reference is new
// texture in the partner, and the slant gives the parabola fractions and the left-right check
// one-label disagreements. Every partner of one `big` shows the same scene.
constexpr int kSceneMargin = 16;
struct Scene {
    int far = 0;
    int slant = 0;
    int near = 0;
    int noise = 0;
};
Image reference_view(const Image& big) {
    return io::crop(big, kSceneMargin, kSceneMargin, big.width - 2 * kSceneMargin,
                    big.height - 2 * kSceneMargin);
}
Image partner_view(const Image& big, Pair pair, const Scene& scene, std::mt19937& rng) {
    const int width = big.width - 2 * kSceneMargin;
    const int height = big.height - 2 * kSceneMargin;
    const Step s = documented_step(pair);
    const auto at = [&](int x, int y, int c) {
        return int{big.at(kSceneMargin + x, kSceneMargin + y, c)};
    };
    const auto in_box = [&](int x, int y) {
        return x >= width / 3 && x < 2 * width / 3 && y >= height / 3 && y < 2 * height / 3;
    };
    Image partner(width, height, big.channels);
    std::uniform_int_distribution<int> jitter(-scene.noise, scene.noise);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const bool box = in_box(x + scene.near * s.x, y + scene.near * s.y);
            const double d =
                scene.far + static_cast<double>(scene.slant) * (x + y) / (width + height);
            const int k = static_cast<int>(std::floor(d));
            const double t = d - k;
            const bool hidden = !box && (in_box(x + k * s.x, y + k * s.y) ||
                                         in_box(x + (k + 1) * s.x, y + (k + 1) * s.y));
            for (int c = 0; c < big.channels; ++c) {
                const double background = (1 - t) * at(x + k * s.x, y + k * s.y, c) +
                                          t * at(x + (k + 1) * s.x, y + (k + 1) * s.y, c);
                const int v = hidden ? byte(rng)
                              : box  ? at(x + scene.near * s.x, y + scene.near * s.y, c)
                                     : static_cast<int>(std::lround(background));
                partner.at(x, y, c) =
                    static_cast<std::uint8_t>(std::clamp(v + jitter(rng), 0, 255));
            }
        }
    }
    return partner;
}

std::string describe(const Stage6Counts& counts, std::size_t pixels) {
    return "valid " + std::to_string(counts.reason[fx::kReasonValid]) + ", border " +
           std::to_string(counts.reason[fx::kReasonBorder]) + ", uniqueness " +
           std::to_string(counts.reason[fx::kReasonUniqueness]) + ", left-right " +
           std::to_string(counts.reason[fx::kReasonLeftRight]) + ", fractional " +
           std::to_string(counts.fractional) + " of " + std::to_string(pixels);
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

// The steps are docs/quad.md's: the fixtures below build their partners from that table, and
// the model and the naive reference read quad::step, so a wrong step cannot cancel out.
TEST(QuadPairs, StepsAreTheDocumentedOnes) {
    for (const Pair pair : kPairs) {
        EXPECT_EQ(step(pair).x, documented_step(pair).x) << name(pair);
        EXPECT_EQ(step(pair).y, documented_step(pair).y) << name(pair);
    }
}

TEST(QuadPairs, ModelEqualsNaiveAndVolumeForm) {
    auto rng = test::seeded_rng(22);
    // Odd sizes, a signed range; a slanted background and an occluding box along each pair's
    // direction, with noise, so that the CA rules and every stage-6 step act: with validation,
    // the uniqueness test and the left-right check reject pixels and the parabola gives
    // fractions (asserted).
    const Scene scene{-3, 2, 1, 8};  // background -3 .. -1, the box at 1; the range is -4 .. 2
    for (const std::string& cost : catalogue::cost_names(catalogue::CostUse::pixel_pair)) {
        for (const Pair pair : kPairs) {
            for (const int channels : {1, 3}) {
                if (cost == "lcdm" && channels == 1) {
                    continue;  // colour only (QuadErrors)
                }
                for (const bool validation : {false, true}) {
                    const Image big = test::random_image(41 + 2 * kSceneMargin,
                                                         37 + 2 * kSceneMargin, channels, rng);
                    const Image reference = reference_view(big);
                    const Image partner = partner_view(big, pair, scene, rng);
                    MatchParams params = small_params(7, -4, validation);
                    params.cost = cost;
                    const auto model = match_pair(pair, reference, partner, params);
                    const std::string what = std::string(cost) + " " + std::string(name(pair)) +
                                             " channels " + std::to_string(channels) +
                                             (validation ? " validated" : " plain");
                    SCOPED_TRACE(what);
                    EXPECT_TRUE(
                        same_validated(naive::match_pair(pair, reference, partner, params), model));
                    EXPECT_TRUE(
                        same_validated(match_pair_volume(pair, reference, partner, params), model));
                    if (validation) {
                        const Stage6Counts counts = stage6_counts(model);
                        std::cout << "[scene] " << what << ": "
                                  << describe(counts, model.fixed.size()) << '\n';
                        EXPECT_GT(counts.reason[fx::kReasonUniqueness], 0);
                        EXPECT_GT(counts.reason[fx::kReasonLeftRight], 0);
                        EXPECT_GT(counts.fractional, 0);
                    }
                }
            }
        }
    }
}

TEST(QuadPairs, KnownShiftsAreRecoveredExactly) {
    auto rng = test::seeded_rng(23);
    for (const std::string& cost : catalogue::cost_names(catalogue::CostUse::pixel_pair)) {
        for (const Pair pair : {Pair::vertical, Pair::diagonal, Pair::horizontal}) {
            for (const int d : {-3, 0, 4}) {
                const auto [reference, partner] = shifted_views(pair, d, 40, 36, 3, rng);
                MatchParams params = small_params(11, -5, false);
                params.cost = cost;
                const auto result = match_pair(pair, reference, partner, params);
                const int reach = invalid_border(params).reach;
                const Step s = documented_step(pair);
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
    // One scene through four cameras: each partner sees it along its own direction (a slanted
    // background, a box in front), so every pair has true matches and its own occlusions, and
    // fusion chooses among pairs that are valid together.
    auto rng = test::seeded_rng(25);
    const Image big = test::random_image(33 + 2 * kSceneMargin, 29 + 2 * kSceneMargin, 3, rng);
    const Scene scene{-1, 2, 3, 6};  // background -1 .. 1, the box at 3; the range is -2 .. 3
    const Image reference = reference_view(big);
    const Image right = partner_view(big, Pair::horizontal, scene, rng);
    const Image below = partner_view(big, Pair::vertical, scene, rng);
    const Image diagonal = partner_view(big, Pair::diagonal, scene, rng);
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
    // What the fixture exercises: a dense fused map, pixels where two or three pairs compete,
    // and every pair winning somewhere.
    const std::size_t pixels = threaded.fused.fixed.size();
    std::size_t fused_valid = 0;
    std::size_t competing = 0;
    std::array<std::size_t, 4> sources{};
    for (std::size_t i = 0; i < pixels; ++i) {
        fused_valid += threaded.fused.valid(i) ? 1 : 0;
        int valid_pairs = 0;
        for (const auto& pair : threaded.pairs) {
            valid_pairs += pair.valid(i) ? 1 : 0;
        }
        competing += valid_pairs >= 2 ? 1 : 0;
        ++sources[threaded.source[i] & 3];
    }
    std::cout << "[scene] fused valid " << fused_valid << " of " << pixels << ", competing "
              << competing << ", won by horizontal " << sources[1] << ", vertical " << sources[2]
              << ", diagonal " << sources[3] << '\n';
    for (const Pair pair : kPairs) {
        std::cout << "[scene] " << name(pair) << ": "
                  << describe(stage6_counts(threaded.pairs[static_cast<std::size_t>(pair)]), pixels)
                  << '\n';
    }
    EXPECT_GE(fused_valid * 10, pixels * 3);  // >= 30 %
    EXPECT_GT(competing, pixels / 10);
    EXPECT_GT(sources[1], 0U);
    EXPECT_GT(sources[2], 0U);
    EXPECT_GT(sources[3], 0U);
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
