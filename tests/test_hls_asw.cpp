// The HLS ASW core (hls/include/stereo/hls/asw.hpp) against the model, bit for bit: the streaming
// top on layered random pairs (odd sizes, signed ranges, census and AD, diameters 3, 5, 11 and
// 31, with and without stage 6) and on a Middlebury crop, against stereo::asw::match with
// Params::separable, every output field (fixed disparity, reason, certainty). Random tests print
// their seed; STEREO_SEED=<n> replays it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

#include "middlebury_crop.hpp"
#include "stage6_counts.hpp"
#include "stereo/asw.hpp"
#include "stereo/hls/asw.hpp"
#include "stereo/hls/asw_match.hpp"
#include "stereo/hls/host.hpp"
#include "stereo/hls/match.hpp"
#include "stereo/matcher.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/test_compare.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo {
namespace {

using test::same_validated;
using test::stage6_counts;

// ---- the tables are the model's ----------------------------------------------------------

TEST(HlsAswTables, EqualTheModelsResponseTables) {
    for (int w = table::kAswMinDiameter; w <= table::kAswMaxDiameter; w += 2) {
        asw::Params params;
        params.diameter = w;
        const asw::ResponseTables tables = asw::response_tables(params);
        const int t = (w - table::kAswMinDiameter) / 2;
        ASSERT_EQ(tables.colour.size(), static_cast<std::size_t>(hls::kAswColourEntries));
        ASSERT_EQ(tables.continuity.size(), static_cast<std::size_t>(hls::kAswContinuityEntries));
        for (std::size_t i = 0; i < tables.colour.size(); ++i) {
            ASSERT_EQ(hls::kAswColour[t][i], tables.colour[i]) << "w " << w << " colour " << i;
        }
        for (std::size_t i = 0; i < tables.continuity.size(); ++i) {
            ASSERT_EQ(hls::kAswContinuity[t][i], tables.continuity[i])
                << "w " << w << " continuity " << i;
        }
        for (int o = 0; o <= w / 2; ++o) {
            ASSERT_EQ(hls::kAswProximity[t][o], tables.proximity[static_cast<std::size_t>(o * o)])
                << "w " << w << " proximity " << o;
        }
    }
}

TEST(HlsAswMean, RestoringDivisionRoundsAsTheModel) {
    // floor((n << shift + floor(s / 2)) / s) for every quotient the passes produce.
    std::mt19937 rng = test::seeded_rng(461);
    std::uniform_int_distribution<int> den(1, table::kAswMaxDiameter * asw::kResponseMax);
    for (int i = 0; i < 20000; ++i) {
        const int s = den(rng);
        for (const int shift : {0, asw::kOutputFracBits}) {
            const int largest = shift == 0 ? fx::kAggMax : fx::kCostMax;
            std::uniform_int_distribution<std::uint32_t> num(
                0, static_cast<std::uint32_t>(s) * static_cast<std::uint32_t>(largest));
            const std::uint32_t n = num(rng);
            const std::uint64_t expected =
                ((std::uint64_t{n} << shift) + static_cast<std::uint64_t>(s / 2)) /
                static_cast<std::uint64_t>(s);
            ASSERT_EQ(hls::asw_mean(n, static_cast<hls::asw_den_t>(s), shift), expected)
                << n << " / " << s << " shift " << shift;
        }
    }
}

// ---- the streaming top -------------------------------------------------------------------

// A textured pair with two depths: a background at disparity `back`, a box at `front` (occluding
// it, so the left-right check has work), piecewise-flat colour patches plus noise (so the colour
// weights vary) and random pixels elsewhere.
io::ImagePair layered_pair(int width, int height, int channels, int back, int front,
                           std::mt19937& rng) {
    Image left(width, height, channels);
    std::uniform_int_distribution<int> value(0, 255);
    std::uniform_int_distribution<int> noise(-6, 6);
    std::uniform_int_distribution<int> patch(3, 9);
    // Patches of constant colour along each row, random lengths.
    for (int y = 0; y < height; ++y) {
        int x = 0;
        while (x < width) {
            const int length = patch(rng);
            int base[3] = {value(rng), value(rng), value(rng)};
            for (int i = 0; i < length && x < width; ++i, ++x) {
                for (int c = 0; c < channels; ++c) {
                    const int v = y % 5 == 0 ? value(rng) : base[c] + noise(rng);
                    left.at(x, y, c) = static_cast<std::uint8_t>(std::clamp(v, 0, 255));
                }
            }
        }
    }
    Image right(width, height, channels);
    const int bx0 = width / 3;
    const int bx1 = width / 3 + std::max(3, width / 4);
    const int by0 = height / 4;
    const int by1 = height / 4 + std::max(2, height / 2);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            // right(x) = left(x + d): the box's pixels where they land, the background elsewhere.
            const int from_front = x + front;
            const bool box = y >= by0 && y < by1 && from_front >= bx0 && from_front < bx1;
            const int source = std::clamp(box ? from_front : x + back, 0, width - 1);
            for (int c = 0; c < channels; ++c) {
                const int v = left.at(source, y, c) + noise(rng) / 3;
                right.at(x, y, c) = static_cast<std::uint8_t>(std::clamp(v, 0, 255));
            }
        }
    }
    return {std::move(left), std::move(right)};
}

// One frame through a freshly built core of the given variant (the host wrapper's path with a
// narrower frame, so that the tests compile few variants).
template <int NDISP, int DIAMETER, class MEASURE>
ValidatedDisparity run_core(const Image& left, const Image& right, const MatchParams& params,
                            const asw::Params& weights, int frames = 1) {
    constexpr int kWidth = 256;
    constexpr int kHeight = 256;
    constexpr int kMaxMinDisp = 16;
    hls::check_asw_core(params, weights, left.width, left.height);
    using Core = hls::asw_pipeline<kWidth, kHeight, NDISP, DIAMETER, kMaxMinDisp, MEASURE>;
    const auto state = std::make_unique<Core>();
    const hls::AswConfig cfg = hls::asw_frame_config(params, weights, left.width, left.height);
    ValidatedDisparity map;
    for (int frame = 0; frame < frames; ++frame) {
        hls::stream<hls::InputBeat> in("test.in");
        hls::stream<hls::OutputBeat> out("test.out");
        hls::push_frame(left, right, in);
        const hls::status_t status =
            hls::stereo_hls_asw_top<kWidth, kHeight, NDISP, DIAMETER, kMaxMinDisp, MEASURE>(
                in, out, cfg, *state);
        EXPECT_EQ(status, 0);
        EXPECT_TRUE(in.empty());
        map = hls::collect_validated(out, left.width, left.height);
        EXPECT_TRUE(out.empty()) << out.size() << " beats too many";
    }
    return map;
}

template <int DIAMETER>
ValidatedDisparity run_cost(const Image& left, const Image& right, const MatchParams& params,
                            const asw::Params& weights) {
    return params.cost == "census"
               ? run_core<16, DIAMETER, hls::census_measure>(left, right, params, weights)
               : run_core<16, DIAMETER, hls::ad_measure>(left, right, params, weights);
}

ValidatedDisparity run_diameter(const Image& left, const Image& right, const MatchParams& params,
                                const asw::Params& weights) {
    switch (weights.diameter) {
        case 3:
            return run_cost<3>(left, right, params, weights);
        case 5:
            return run_cost<5>(left, right, params, weights);
        case 11:
            return run_cost<11>(left, right, params, weights);
        case 31:
            return run_cost<31>(left, right, params, weights);
        default:
            throw std::invalid_argument("no test variant of diameter " +
                                        std::to_string(weights.diameter));
    }
}

asw::Params separable(int diameter) {
    asw::Params weights;
    weights.diameter = diameter;
    weights.separable = true;
    weights.threads = 1;
    return weights;
}

struct Case {
    int width, height, diameter, ndisp, min_disp, back, front;
};

// Every case with census and AD, grey and colour, stage 6 off and every step on.
void expect_cases_equal_model(const Case* begin, const Case* end, std::uint32_t salt) {
    std::mt19937 rng = test::seeded_rng(static_cast<int>(salt));
    test::Stage6Counts all;
    int pixels = 0;
    for (const Case* c = begin; c != end; ++c) {
        for (const int channels : {3, 1}) {
            const auto [left, right] =
                layered_pair(c->width, c->height, channels, c->back, c->front, rng);
            for (const char* cost : {"census", "ad"}) {
                for (const bool stage6 : {false, true}) {
                    MatchParams params;
                    params.ndisp = c->ndisp;
                    params.min_disp = c->min_disp;
                    params.cost = cost;
                    params.validation = stage6 ? ValidationParams::all_on() : ValidationParams{};
                    params.validation.lr_tolerance = stage6 ? 1 : 0;
                    const asw::Params weights = separable(c->diameter);
                    const ValidatedDisparity expected = asw::match(left, right, params, weights);
                    const ValidatedDisparity actual = run_diameter(left, right, params, weights);
                    ASSERT_TRUE(same_validated(expected, actual))
                        << c->width << "x" << c->height << " w " << c->diameter << " ndisp "
                        << c->ndisp << " min_disp " << c->min_disp << " " << cost << " " << channels
                        << " channel(s), stage 6 " << (stage6 ? "on" : "off");
                    if (stage6) {
                        const test::Stage6Counts counts = stage6_counts(expected);
                        for (std::size_t r = 0; r < counts.reason.size(); ++r) {
                            all.reason[r] += counts.reason[r];
                        }
                        all.fractional += counts.fractional;
                        all.negative += counts.negative;
                        pixels += c->width * c->height;
                    }
                }
            }
        }
    }
    // The comparisons must have exercised stage 6: valid pixels, sub-pixel fractions, and pixels
    // invalidated by the border, uniqueness and the left-right check.
    EXPECT_GT(all.reason[fx::kReasonValid], pixels * 3 / 10);
    EXPECT_GT(all.fractional, 0);
    EXPECT_GT(all.reason[fx::kReasonUniqueness], 0);
    EXPECT_GT(all.reason[fx::kReasonLeftRight], 0);
    std::cout << "stage 6 over " << pixels << " pixels: valid " << all.reason[fx::kReasonValid]
              << ", border " << all.reason[fx::kReasonBorder] << ", uniqueness "
              << all.reason[fx::kReasonUniqueness] << ", left-right "
              << all.reason[fx::kReasonLeftRight] << ", fractional " << all.fractional
              << ", negative " << all.negative << '\n';
}

TEST(HlsAsw, SmallDiametersEqualModel) {
    // Widths and heights of no particular multiple, the smallest the window allows (the image as
    // tall as the window plus one), label counts up to the 16 lanes, signed ranges.
    const Case cases[] = {{37, 13, 3, 9, 0, 3, 6},   {23, 4, 3, 5, -2, 1, 3},
                          {41, 17, 5, 12, 3, 5, 9},  {19, 6, 5, 16, 0, 2, 7},
                          {29, 11, 5, 7, -5, -3, 1}, {53, 9, 3, 16, -8, -4, 2}};
    expect_cases_equal_model(std::begin(cases), std::end(cases), 4601);
}

TEST(HlsAsw, HardwareDiameterEqualsModel) {
    static_assert(asw::kHardwareDiameter == 11);
    const Case cases[] = {
        {61, 23, 11, 16, 0, 4, 10}, {47, 12, 11, 11, -4, -2, 3}, {33, 19, 11, 13, 6, 7, 12}};
    expect_cases_equal_model(std::begin(cases), std::end(cases), 4602);
}

TEST(HlsAsw, LargeDiameterEqualsModel) {
    const Case cases[] = {{45, 33, 31, 10, 0, 2, 6}, {39, 32, 31, 16, -3, 0, 5}};
    expect_cases_equal_model(std::begin(cases), std::end(cases), 4603);
}

TEST(HlsAsw, FlatAndExtremeImagesEqualModel) {
    // Constant and two-level images: equal costs everywhere, so pass 1's winner and the WTA
    // decide by their tie rule (the smaller label), and extreme differences saturate every cost.
    std::mt19937 rng = test::seeded_rng(4609);
    std::bernoulli_distribution coin(0.5);
    Image zero(31, 12, 3);
    Image full(31, 12, 3);
    std::fill(full.pixels.begin(), full.pixels.end(), std::uint8_t{255});
    Image stripes(31, 12, 3);
    for (int y = 0; y < stripes.height; ++y) {
        for (int x = 0; x < stripes.width; ++x) {
            const std::uint8_t v = (x / 4 + y / 3) % 2 == 0 ? 40 : 200;
            for (int c = 0; c < 3; ++c) {
                stripes.at(x, y, c) = v;
            }
        }
    }
    Image speckle(31, 12, 3);
    for (auto& p : speckle.pixels) {
        p = coin(rng) ? 255 : 0;
    }
    const std::pair<const Image*, const Image*> pairs[] = {
        {&zero, &zero}, {&full, &zero}, {&stripes, &stripes}, {&stripes, &zero}, {&speckle, &full}};
    for (std::size_t i = 0; i < std::size(pairs); ++i) {
        const auto [left, right] = pairs[i];
        for (const char* cost : {"census", "ad"}) {
            for (const int diameter : {3, 11}) {
                MatchParams params;
                params.ndisp = 9;
                params.min_disp = -2;
                params.cost = cost;
                params.validation = ValidationParams::all_on();
                const asw::Params weights = separable(diameter);
                ASSERT_TRUE(same_validated(asw::match(*left, *right, params, weights),
                                           run_diameter(*left, *right, params, weights)))
                    << cost << " w " << diameter << " pair " << i;
            }
        }
    }
}

TEST(HlsAsw, ContinuityAcrossLargeJumpsEqualsModel) {
    // The continuity factor is below 255 only for label jumps above 255 / w (23 at w = 11, 8 at
    // w = 31): 64 lanes and boxes far in front of the background, so that pass 1's labels, their
    // history and its tie rule (flat images: equal costs) decide pass 2's weights.
    std::mt19937 rng = test::seeded_rng(4610);
    struct Jump {
        int width, height, ndisp, min_disp, back, front;
    };
    const Jump jumps[] = {{97, 35, 56, 0, 3, 41}, {83, 33, 64, -6, -2, 30}};
    Image flat(97, 35, 3);
    std::fill(flat.pixels.begin(), flat.pixels.end(), std::uint8_t{90});
    for (const Jump& j : jumps) {
        const auto [left, right] = layered_pair(j.width, j.height, 3, j.back, j.front, rng);
        for (const char* cost : {"census", "ad"}) {
            for (const bool stage6 : {false, true}) {
                MatchParams params;
                params.ndisp = j.ndisp;
                params.min_disp = j.min_disp;
                params.cost = cost;
                params.validation = stage6 ? ValidationParams::all_on() : ValidationParams{};
                for (const int diameter : {11, 31}) {
                    const asw::Params weights = separable(diameter);
                    const auto run =
                        diameter == 11
                            ? (params.cost == "census" ? &run_core<64, 11, hls::census_measure>
                                                       : &run_core<64, 11, hls::ad_measure>)
                            : (params.cost == "census" ? &run_core<64, 31, hls::census_measure>
                                                       : &run_core<64, 31, hls::ad_measure>);
                    ASSERT_TRUE(same_validated(asw::match(left, right, params, weights),
                                               run(left, right, params, weights, 1)))
                        << j.width << "x" << j.height << " " << cost << " w " << diameter;
                    if (j.width == flat.width && j.height == flat.height) {
                        ASSERT_TRUE(same_validated(asw::match(flat, flat, params, weights),
                                                   run(flat, flat, params, weights, 1)))
                            << "flat " << cost << " w " << diameter;
                    }
                }
            }
        }
    }
}

TEST(HlsAsw, OtherTruncationsEqualModel) {
    // The cost's cap is a runtime value: none for AD, and a cap for census.
    std::mt19937 rng = test::seeded_rng(4604);
    const auto [left, right] = layered_pair(35, 14, 3, 2, 5, rng);
    for (const char* cost : {"census", "ad"}) {
        for (const int truncation : {0, 93, 765}) {
            MatchParams params;
            params.ndisp = 10;
            params.cost = cost;
            params.validation = ValidationParams::all_on();
            asw::Params weights = separable(5);
            weights.truncation = truncation;
            ASSERT_TRUE(same_validated(asw::match(left, right, params, weights),
                                       run_diameter(left, right, params, weights)))
                << cost << " truncation " << truncation;
        }
    }
}

TEST(HlsAsw, FramesBackToBackEqualModel) {
    // Three frames through one core without clearing it: only the coordinates are reset.
    std::mt19937 rng = test::seeded_rng(4605);
    const auto [left, right] = layered_pair(27, 15, 3, 3, 7, rng);
    MatchParams params;
    params.ndisp = 12;
    params.min_disp = -2;
    params.cost = "census";
    params.validation = ValidationParams::all_on();
    const asw::Params weights = separable(5);
    const ValidatedDisparity actual =
        run_core<16, 5, hls::census_measure>(left, right, params, weights, 3);
    EXPECT_TRUE(same_validated(asw::match(left, right, params, weights), actual));
}

TEST(HlsAsw, LatencyIsTheFrameSteps) {
    // The first frame pixel enters the output register at step asw_pipeline_delay - 1 exactly.
    std::mt19937 rng = test::seeded_rng(4606);
    const auto [left, right] = layered_pair(21, 9, 3, 1, 4, rng);
    for (const int min_disp : {0, -3, 2}) {
        const auto run = [&](auto core, int expected) {
            hls::AswConfig cfg;
            cfg.width = left.width;
            cfg.height = left.height;
            cfg.ndisp = 8;
            cfg.min_disp = min_disp;
            core->reset();
            int first = -1;
            for (int step = 0; step < 4 * left.width * left.height && first < 0; ++step) {
                const int x = step % left.width;
                const int y = step / left.width;
                const hls::Rgb l = y < left.height ? hls::rgb(left, x, y) : hls::Rgb{};
                const hls::Rgb r = y < left.height ? hls::rgb(right, x, y) : hls::Rgb{};
                core->step(hls::to_coord(x), hls::to_coord(y), l, r, cfg);
                if (core->out_x() == 0 && core->out_y() == 0) {
                    first = step;
                }
            }
            EXPECT_EQ(first, expected - 1) << "min_disp " << min_disp;
        };
        run(std::make_unique<hls::asw_pipeline<64, 64, 8, 5, 4, hls::ad_measure>>(),
            hls::asw_pipeline_delay<8, 5, hls::ad_measure>(left.width, min_disp));
        run(std::make_unique<hls::asw_pipeline<64, 64, 8, 5, 4, hls::census_measure>>(),
            hls::asw_pipeline_delay<8, 5, hls::census_measure>(left.width, min_disp));
    }
}

// ---- the host wrapper and the engine -------------------------------------------------------

TEST(HlsAsw, MiddleburyCropEqualsModel) {
    // Teddy at the hardware configuration (census, w = 11) and the thesis' cost (AD) at w = 31,
    // 60 labels (the 64-lane variant), stage 6 as `stereo match` runs it and off.
    struct Crop {
        int x0, y0, width, height, diameter;
        const char* cost;
    };
    const Crop crops[] = {{150, 120, 97, 41, 11, "census"}, {300, 200, 83, 45, 31, "ad"}};
    for (const Crop& c : crops) {
        const auto pair = test::middlebury_crop("teddy", c.x0, c.y0, c.width, c.height);
        if (!pair) {
            GTEST_SKIP() << "Middlebury teddy not found under " << io::data_dir();
        }
        for (const bool stage6 : {true, false}) {
            MatchParams params;
            params.ndisp = 60;
            params.cost = c.cost;
            params.validation.uniqueness = false;  // stereo match's defaults
            params.validation.left_right = stage6;
            params.validation.lr_tolerance = 1;
            params.validation.subpixel = stage6;
            const asw::Params weights = separable(c.diameter);
            const ValidatedDisparity expected =
                asw::match(pair->left, pair->right, params, weights);
            const ValidatedDisparity actual =
                hls::asw_match_validated(pair->left, pair->right, params, weights);
            EXPECT_TRUE(same_validated(expected, actual))
                << "teddy " << c.width << "x" << c.height << " w " << c.diameter << " " << c.cost
                << " stage 6 " << (stage6 ? "on" : "off");
            const test::Stage6Counts counts = stage6_counts(expected);
            EXPECT_GT(counts.reason[fx::kReasonValid], c.width * c.height / 2);
        }
    }
}

TEST(HlsAsw, EngineHlsEqualsEngineModel) {
    // `stereo match --aggregation asw --separable --engine hls` through the registry.
    MatcherRegistry registry;
    register_model_matchers(registry);
    hls::register_matchers(registry);
    std::mt19937 rng = test::seeded_rng(4607);
    const auto [left, right] = layered_pair(43, 21, 3, 3, 8, rng);
    MatchConfig config;
    config.pipeline.ndisp = 20;
    config.pipeline.min_disp = -1;
    config.pipeline.cost = "census";
    config.pipeline.validation = ValidationParams::all_on();
    config.asw = separable(7);
    const MatchResult model = registry.create("asw", "model", config)->compute(left, right);
    const MatchResult hls = registry.create("asw", "hls", config)->compute(left, right);
    EXPECT_TRUE(same_validated(model.validated, hls.validated));
    EXPECT_TRUE(model.disparity == hls.disparity);
}

TEST(HlsAsw, RefusesWhatTheCoreDoesNotCompute) {
    std::mt19937 rng = test::seeded_rng(4608);
    const auto [left, right] = layered_pair(40, 40, 3, 1, 2, rng);
    MatchParams params;
    params.ndisp = 8;
    const auto refuses = [&](const MatchParams& p, const asw::Params& w, const char* what) {
        EXPECT_THROW(hls::asw_match_validated(left, right, p, w), std::invalid_argument) << what;
    };
    asw::Params full = separable(5);
    full.separable = false;
    refuses(params, full, "the full (non-separable) variant");
    asw::Params q = separable(5);
    q.continuity = false;
    refuses(params, q, "no continuity");
    q = separable(5);
    q.response = asw::Response::exp;
    refuses(params, q, "exp response");
    q = separable(5);
    q.right_weights = false;
    refuses(params, q, "left weights only");
    refuses(params, separable(33), "diameter 33");
    MatchParams lcdm = params;
    lcdm.cost = "lcdm";
    refuses(lcdm, separable(5), "lcdm");
    MatchParams far = params;
    far.min_disp = 65;
    refuses(far, separable(5), "min_disp 65");
}

}  // namespace
}  // namespace stereo
