// The HLS kernels (hls/) against the golden model, bit for bit: every stage object streamed one
// pixel step at a time against the model's stage function, and the streaming top against
// stereo::match on random, odd-sized, grey, constant and extreme images and the Middlebury pairs.
// Random tests print their seed; STEREO_SEED=<n> replays it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "stage6_counts.hpp"
#include "stereo/hls/aggregate.hpp"
#include "stereo/hls/ca_rule.hpp"
#include "stereo/hls/census.hpp"
#include "stereo/hls/cost.hpp"
#include "stereo/hls/cost_lcdm.hpp"
#include "stereo/hls/host.hpp"
#include "stereo/hls/match.hpp"
#include "stereo/hls/stream.hpp"
#include "stereo/hls/top.hpp"
#include "stereo/hls/wta.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/search.hpp"
#include "stereo/stages.hpp"
#include "stereo/stages/census.hpp"
#include "stereo_hls_synth_top.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/middlebury.hpp"
#include "stereo_io/test_compare.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo {
namespace {

using Value = Dsi::Value;

std::mt19937 seeded(std::uint32_t salt) {
    return std::mt19937(test::test_seed() ^ salt);
}

// ---- comparison with messages ------------------------------------------------------------

using test::same_map;
using test::same_validated;  // stage 6: fixed disparity, reason and certainty of every pixel
using test::same_volume;
using test::stage6_counts;
using test::Stage6Counts;

// ---- streaming one stage ----------------------------------------------------------------

// Steps `stage` over a width x height frame in raster order, then over flush steps whose
// coordinates continue the raster, exactly as stereo_hls_top does. feed(x, y) performs one step
// (y >= height while flushing); take(x, y) reads the output register whenever it holds a frame
// pixel. Checks that every frame pixel leaves exactly once and in raster order, and returns the
// number of flush steps it took: the stage's latency minus one.
template <typename Stage, typename Feed, typename Take>
int stream_frame(Stage& stage, int width, int height, Feed feed, Take take) {
    stage.reset();
    const int pixels = width * height;
    int emitted = 0;
    int step = 0;
    for (; emitted < pixels; ++step) {
        if (step > pixels + 40 * (width + 40)) {
            ADD_FAILURE() << "only " << emitted << " of " << pixels << " pixels left the stage";
            break;
        }
        feed(step % width, step / width);
        const int x = stage.out_x();
        const int y = stage.out_y();
        if (x >= 0 && x < width && y >= 0 && y < height) {
            EXPECT_EQ(y * width + x, emitted) << "output out of raster order at step " << step;
            take(x, y);
            ++emitted;
        }
    }
    return step - pixels;
}

hls::Rgb rgb_at(const Image& image, int x, int y) {
    const int c1 = image.channels == 3 ? 1 : 0;
    const int c2 = image.channels == 3 ? 2 : 0;
    return hls::Rgb{image.at(x, y, 0), image.at(x, y, c1), image.at(x, y, c2)};
}

// A volume whose planes sit around their own level with small noise (so that the CA rules' 2|n
// - c| < c tests often agree) and 10 % outliers anywhere in [0, max] (so that they often fail).
Dsi banded_volume(int width, int height, int ndisp, int max, std::mt19937& rng) {
    Dsi volume(width, height, ndisp);
    std::uniform_int_distribution<int> level(max / 8, max / 2);
    std::uniform_int_distribution<int> noise(-max / 20, max / 20);
    std::uniform_int_distribution<int> any(0, max);
    std::bernoulli_distribution outlier(0.1);
    for (int d = 0; d < ndisp; ++d) {
        const int base = level(rng);
        for (auto& cell : volume.plane(d)) {
            const int v = outlier(rng) ? any(rng) : base + noise(rng);
            cell = static_cast<Value>(std::clamp(v, 0, max));
        }
    }
    return volume;
}

Dsi random_volume(int width, int height, int ndisp, int low, int high, std::mt19937& rng) {
    Dsi volume(width, height, ndisp);
    std::uniform_int_distribution<int> value(low, high);
    for (int d = 0; d < ndisp; ++d) {
        for (auto& cell : volume.plane(d)) {
            cell = static_cast<Value>(value(rng));
        }
    }
    return volume;
}

// Streams `volume` through a volume stage and returns its output volume with `out_planes`
// planes. Lanes d >= volume.ndisp() and the flush steps carry random garbage in [0, max], the
// range of real data, which the stage must never use. step(x, y, in) performs one step.
template <int LANES, typename In, typename Stage, typename Step>
Dsi stream_volume(Stage& stage, const Dsi& volume, int out_planes, Step step, int max,
                  std::mt19937& rng, int* flush_steps) {
    const int width = volume.width();
    const int height = volume.height();
    Dsi out(width, height, out_planes);
    std::uniform_int_distribution<int> garbage(0, max);
    In in[LANES];
    const int flushes = stream_frame(
        stage, width, height,
        [&](int x, int y) {
            for (int d = 0; d < LANES; ++d) {
                in[d] = y < height && d < volume.ndisp() ? static_cast<In>(volume.at(x, y, d))
                                                         : static_cast<In>(garbage(rng));
            }
            step(static_cast<hls::coord_t>(x), static_cast<hls::coord_t>(y), in);
        },
        [&](int x, int y) {
            for (int d = 0; d < out_planes; ++d) {
                out.at(x, y, d) = stage.out_data()[d];
            }
        });
    if (flush_steps != nullptr) {
        *flush_steps = flushes;
    }
    return out;
}

template <int WINDOW>
void centred_kernel(int window, double sigma, hls::tap_t (&kernel)[WINDOW]) {
    const std::vector<std::int32_t> taps = gaussian_kernel(window, sigma);
    std::fill(std::begin(kernel), std::end(kernel), hls::tap_t{0});
    for (int i = 0; i < window; ++i) {
        kernel[(WINDOW - window) / 2 + i] = static_cast<hls::tap_t>(taps[i]);
    }
}

// ---- stage: cost --------------------------------------------------------------------------

// A cost stage (AD or LCDM kernel) against the model's volume `model`, every lane of every
// pixel, with garbage flush pixels and two frames back to back through one object (the delay
// line is never cleared).
template <class Stage, int NDISP>
void check_cost_stage(const Image& left, const Image& right, const Dsi& model, std::mt19937& rng) {
    const auto stage = std::make_unique<Stage>();
    std::uniform_int_distribution<int> garbage(0, 255);
    const auto noise = [&] {
        return hls::Rgb{static_cast<hls::pixel_t>(garbage(rng)),
                        static_cast<hls::pixel_t>(garbage(rng)),
                        static_cast<hls::pixel_t>(garbage(rng))};
    };
    // Two frames back to back through one object: the delay line is never cleared.
    for (int frame = 0; frame < 2; ++frame) {
        Dsi out(left.width, left.height, NDISP);
        const int flushes = stream_frame(
            *stage, left.width, left.height,
            [&](int x, int y) {
                const bool in_frame = y < left.height;
                stage->step(static_cast<hls::coord_t>(x), static_cast<hls::coord_t>(y),
                            in_frame ? rgb_at(left, x, y) : noise(),
                            in_frame ? rgb_at(right, x, y) : noise(), left.width, 0);
            },
            [&](int x, int y) {
                for (int d = 0; d < NDISP; ++d) {
                    out.at(x, y, d) = stage->out_data()[d];
                }
            });
        EXPECT_EQ(flushes + 1, 1) << "latency";
        EXPECT_TRUE(same_volume(model, out, NDISP))
            << left.width << "x" << left.height << "x" << left.channels << ", NDISP " << NDISP;
    }
}

template <int NDISP>
void check_cost(const Image& left, const Image& right, std::mt19937& rng) {
    check_cost_stage<hls::cost<NDISP, table::kDefaultMaxMinDisp>, NDISP>(
        left, right, cost(left, right, NDISP), rng);
}

TEST(HlsCost, EqualsModelColourAndGrey) {
    auto rng = seeded(1);
    for (const auto& [width, height, channels] :
         {std::tuple{37, 23, 3}, std::tuple{37, 23, 1}, std::tuple{5, 3, 3}, std::tuple{1, 1, 3},
          std::tuple{70, 9, 3}}) {
        const Image left = test::random_image(width, height, channels, rng);
        const Image right = test::random_image(width, height, channels, rng);
        check_cost<1>(left, right, rng);
        check_cost<16>(left, right, rng);
        check_cost<64>(left, right, rng);  // more lanes than columns in most frames
    }
}

// The LCDM cost stage against the model's "lcdm" plug-in.
template <int NDISP>
void check_cost_lcdm(const Image& left, const Image& right, std::mt19937& rng) {
    check_cost_stage<hls::cost_lcdm<NDISP, table::kDefaultMaxMinDisp>, NDISP>(
        left, right, cost_volume(*make_cost("lcdm"), left, right, NDISP), rng);
}

TEST(HlsCostLcdm, EqualsModel) {
    auto rng = seeded(21);
    for (const auto& [width, height] :
         {std::pair{37, 23}, std::pair{5, 3}, std::pair{1, 1}, std::pair{70, 9}}) {
        const Image left = test::random_image(width, height, 3, rng);
        const Image right = test::random_image(width, height, 3, rng);
        check_cost_lcdm<1>(left, right, rng);
        check_cost_lcdm<16>(left, right, rng);
    }
    // The faces of the RGB cube (every hue sector, every tie).
    const auto [cube, reversed] = test::rgb_cube_pair(18 * 18, 6);
    check_cost_lcdm<16>(cube, reversed, rng);
}

// ---- stage: aggregate ----------------------------------------------------------------------

template <int WIDTH, int NDISP, int WINDOW>
void check_aggregate(std::mt19937& rng, const std::vector<int>& windows) {
    // One object for all frames: sizes change, the line buffers are never cleared.
    const auto stage = std::make_unique<hls::aggregate<WIDTH, NDISP, WINDOW>>();
    constexpr int R = WINDOW / 2;
    const std::vector<std::pair<int, int>> sizes = {{37, 23}, {4, 3}, {1, 5}, {5, 1}, {30, 40}};
    for (const int window : windows) {
        for (const auto& [width, height] : sizes) {
            for (const bool extreme : {false, true}) {
                const Dsi costs =
                    extreme ? random_volume(width, height, NDISP, fx::kCostMax, fx::kCostMax, rng)
                            : random_volume(width, height, NDISP, 0, fx::kCostMax, rng);
                const double sigma = window <= 3 ? 1.0 : fx::kDefaultSigma;
                hls::tap_t kernel[WINDOW];
                centred_kernel<WINDOW>(window, sigma, kernel);
                int flushes = 0;
                const Dsi out = stream_volume<NDISP, hls::cost_t>(
                    *stage, costs, NDISP,
                    [&](hls::coord_t x, hls::coord_t y, const hls::cost_t(&in)[NDISP]) {
                        stage->step(x, y, in, width, height, kernel);
                    },
                    fx::kCostMax, rng, &flushes);
                EXPECT_TRUE(
                    same_volume(aggregate(costs, gaussian_kernel(window, sigma)), out, NDISP))
                    << width << "x" << height << ", NDISP " << NDISP << ", WINDOW " << WINDOW
                    << ", window " << window << (extreme ? ", all costs maximal" : "");
                EXPECT_EQ(flushes + 1, R * width + R + 2) << "latency R*W + R + 2";
            }
        }
    }
}

TEST(HlsAggregate, EqualsModelForFullAndCentredWindows) {
    auto rng = seeded(2);
    check_aggregate<64, 8, 5>(rng, {5, 3, 1});
    check_aggregate<64, 4, 11>(rng, {11, 7});  // frames narrower than the radius too
    check_aggregate<64, 3, 1>(rng, {1});
    check_aggregate<64, 2, 31>(rng, {31, 13});
}

// ---- stages: ca_rule1, ca_rule2 ----------------------------------------------------------

const std::vector<std::pair<int, int>>& rule_sizes() {
    static const std::vector<std::pair<int, int>> sizes = {{37, 23}, {2, 2}, {1, 1},  {1, 7},
                                                           {7, 1},   {3, 3}, {40, 30}};
    return sizes;
}

// Aggregated volumes of a real match (shifted random images) besides the synthetic ones.
Dsi realistic_volume(int width, int height, int ndisp, std::mt19937& rng) {
    const auto [left, right] = test::shifted_pair(width, height, 3, 2, 10, rng);
    return aggregate(cost(left, right, ndisp), gaussian_kernel(5, 2.0));
}

template <int WIDTH, int NDISP, typename Stage, typename Model>
void check_rule(Stage& stage, Model model, std::mt19937& rng, const char* name) {
    for (const auto& [width, height] : rule_sizes()) {
        for (int ndisp : {NDISP, std::max(1, NDISP - 3)}) {  // lanes >= ndisp hold garbage
            for (int kind = 0; kind < 2; ++kind) {
                const Dsi volume = kind == 0 ? banded_volume(width, height, ndisp, fx::kAggMax, rng)
                                             : realistic_volume(width, height, ndisp, rng);
                for (const bool use_ca : {true, false}) {
                    int flushes = 0;
                    const Dsi out = stream_volume<NDISP, hls::agg_t>(
                        stage, volume, ndisp,
                        [&](hls::coord_t x, hls::coord_t y, const hls::agg_t(&in)[NDISP]) {
                            stage.step(x, y, in, width, height, ndisp, use_ca);
                        },
                        fx::kAggMax, rng, &flushes);
                    EXPECT_TRUE(same_volume(use_ca ? model(volume) : volume, out, ndisp))
                        << name << " " << width << "x" << height << ", NDISP " << NDISP
                        << ", ndisp " << ndisp << (kind == 0 ? ", banded" : ", realistic")
                        << (use_ca ? "" : ", CA off");
                    EXPECT_EQ(flushes + 1, width + 2) << name << " latency W + 2";
                }
            }
        }
    }
}

TEST(HlsCaRule1, EqualsModel) {
    auto rng = seeded(3);
    check_rule<64, 8>(
        *std::make_unique<hls::ca_rule1<64, 8>>(), [](const Dsi& v) { return ca_rule1(v); }, rng,
        "ca_rule1");
    // No d-neighbour at all.
    check_rule<64, 1>(
        *std::make_unique<hls::ca_rule1<64, 1>>(), [](const Dsi& v) { return ca_rule1(v); }, rng,
        "ca_rule1");
}

TEST(HlsCaRule2, EqualsModel) {
    auto rng = seeded(4);
    check_rule<64, 8>(
        *std::make_unique<hls::ca_rule2<64, 8>>(), [](const Dsi& v) { return ca_rule2(v); }, rng,
        "ca_rule2");
}

// ---- stage: wta -------------------------------------------------------------------------

template <int NDISP>
void check_wta(std::mt19937& rng) {
    const auto stage = std::make_unique<hls::wta<NDISP>>();
    for (const auto& [width, height] : {std::pair{37, 23}, std::pair{12, 12}, std::pair{3, 3}}) {
        for (int ndisp : {NDISP, std::max(1, NDISP - 3)}) {
            // Few distinct values, so ties are common; lanes >= ndisp carry 0, which would win.
            const Dsi volume = random_volume(width, height, ndisp, 0, 12, rng);
            for (int radius = 0; radius <= 3; ++radius) {
                for (const bool use_ca : {true, false}) {
                    DisparityMap out(width, height);
                    hls::agg_t in[NDISP];
                    const int flushes = stream_frame(
                        *stage, width, height,
                        [&](int x, int y) {
                            for (int d = 0; d < NDISP; ++d) {
                                in[d] = y < height && d < ndisp
                                            ? static_cast<hls::agg_t>(volume.at(x, y, d))
                                            : hls::agg_t{0};
                            }
                            stage->step(static_cast<hls::coord_t>(x), static_cast<hls::coord_t>(y),
                                        in, width, height, ndisp, radius, use_ca, 0);
                        },
                        [&](int x, int y) {
                            out.disparity[out.index(x, y)] = stage->out_disparity();
                            out.valid[out.index(x, y)] = stage->out_valid() ? 1 : 0;
                        });
                    EXPECT_TRUE(
                        same_map(wta(volume, InvalidBorder{radius + (use_ca ? 1 : 0)}), out))
                        << width << "x" << height << ", NDISP " << NDISP << ", ndisp " << ndisp
                        << ", radius " << radius << (use_ca ? ", CA" : "");
                    EXPECT_EQ(flushes + 1, 1) << "latency";
                }
            }
        }
    }
}

TEST(HlsWta, EqualsModelWithTiesAndBorders) {
    auto rng = seeded(5);
    check_wta<1>(rng);
    check_wta<5>(rng);  // not a power of two: padded leaves
    check_wta<16>(rng);
}

// ---- all stages on a real pair ----------------------------------------------------------

// Each stage fed the model's output of the stage before it, on Tsukuba: volumes with real
// structure (and the Middlebury ndisp and default window) rather than random ones.
TEST(HlsStages, EachStageEqualsModelOnTsukuba) {
    const auto& scene = io::middlebury2003_scenes().front();
    const auto data = io::load_scene(io::data_dir(), scene);
    if (!data) {
        GTEST_SKIP() << "Middlebury " << scene.name << " not found under " << io::data_dir();
    }
    constexpr int kWidth = 512;
    constexpr int kNdisp = 16;
    constexpr int kWindow = fx::kDefaultWindow;
    ASSERT_EQ(scene.ndisp, kNdisp);
    const Image& left = data->pair.left;
    const Image& right = data->pair.right;
    const int width = left.width;
    const int height = left.height;
    ASSERT_LE(width, kWidth);
    auto rng = seeded(15);

    check_cost<kNdisp>(left, right, rng);
    const Dsi costs = cost(left, right, kNdisp);

    const auto aggregator = std::make_unique<hls::aggregate<kWidth, kNdisp, kWindow>>();
    hls::tap_t kernel[kWindow];
    centred_kernel<kWindow>(kWindow, fx::kDefaultSigma, kernel);
    int flushes = 0;
    const Dsi aggregated = aggregate(costs, gaussian_kernel(kWindow, fx::kDefaultSigma));
    EXPECT_TRUE(
        same_volume(aggregated,
                    stream_volume<kNdisp, hls::cost_t>(
                        *aggregator, costs, kNdisp,
                        [&](hls::coord_t x, hls::coord_t y, const hls::cost_t(&in)[kNdisp]) {
                            aggregator->step(x, y, in, width, height, kernel);
                        },
                        fx::kCostMax, rng, &flushes),
                    kNdisp))
        << "aggregate";

    // The two CA rules have one interface: each is streamed the model's output of the stage
    // before it.
    const auto expect_rule = [&](auto& rule, const Dsi& in, const Dsi& expected, const char* name) {
        EXPECT_TRUE(
            same_volume(expected,
                        stream_volume<kNdisp, hls::agg_t>(
                            rule, in, kNdisp,
                            [&](hls::coord_t x, hls::coord_t y, const hls::agg_t(&beat)[kNdisp]) {
                                rule.step(x, y, beat, width, height, kNdisp, true);
                            },
                            fx::kAggMax, rng, &flushes),
                        kNdisp))
            << name;
    };
    const Dsi after_rule1 = ca_rule1(aggregated);
    expect_rule(*std::make_unique<hls::ca_rule1<kWidth, kNdisp>>(), aggregated, after_rule1,
                "ca_rule1");
    const Dsi after_rule2 = ca_rule2(after_rule1);
    expect_rule(*std::make_unique<hls::ca_rule2<kWidth, kNdisp>>(), after_rule1, after_rule2,
                "ca_rule2");

    const auto winner = std::make_unique<hls::wta<kNdisp>>();
    const MatchParams params{kNdisp, kWindow, fx::kDefaultSigma, true};
    DisparityMap out(width, height);
    stream_frame(
        *winner, width, height,
        [&](int x, int y) {
            hls::agg_t in[kNdisp];
            for (int d = 0; d < kNdisp; ++d) {
                in[d] = y < height ? static_cast<hls::agg_t>(after_rule2.at(x, y, d)) : 0;
            }
            winner->step(static_cast<hls::coord_t>(x), static_cast<hls::coord_t>(y), in, width,
                         height, kNdisp, kWindow / 2, true, 0);
        },
        [&](int x, int y) {
            out.disparity[out.index(x, y)] = winner->out_disparity();
            out.valid[out.index(x, y)] = winner->out_valid() ? 1 : 0;
        });
    const DisparityMap expected = wta(after_rule2, invalid_border(params));
    EXPECT_TRUE(same_map(expected, out)) << "wta";
    EXPECT_TRUE(same_map(match(left, right, params), out)) << "the stages compose to match()";
}

// ---- the streaming top ---------------------------------------------------------------------

template <int WIDTH, int HEIGHT, int NDISP, int WINDOW, int MAX_MIN_DISP>
ValidatedDisparity run_top_validated(
    hls::pipeline<WIDTH, HEIGHT, NDISP, WINDOW, MAX_MIN_DISP>& state, const Image& left,
    const Image& right, const MatchParams& params, hls::status_t expected_status = 0) {
    hls::stream<hls::InputBeat> in("test.in");
    hls::stream<hls::OutputBeat> out("test.out");
    hls::push_frame(left, right, in);
    const hls::status_t status = hls::stereo_hls_top<WIDTH, HEIGHT, NDISP, WINDOW, MAX_MIN_DISP>(
        in, out, hls::frame_config<WINDOW>(params, left.width, left.height), state);
    EXPECT_EQ(status, expected_status);
    EXPECT_TRUE(in.empty());
    EXPECT_EQ(out.size(), static_cast<std::size_t>(left.width) * left.height)
        << "one output beat per input pixel";
    return hls::collect_validated(out, left.width, left.height);
}

template <int WIDTH, int HEIGHT, int NDISP, int WINDOW, int MAX_MIN_DISP>
DisparityMap run_top(hls::pipeline<WIDTH, HEIGHT, NDISP, WINDOW, MAX_MIN_DISP>& state,
                     const Image& left, const Image& right, const MatchParams& params,
                     hls::status_t expected_status = 0) {
    return to_label_map(run_top_validated(state, left, right, params, expected_status));
}

// Steps a reset pipeline through the pair's raster, then zero pixels, `steps` times in all, and
// returns the step at which the frame's last pixel reached the output register (-1: never).
template <class Pipeline, int WINDOW>
int last_output_step(Pipeline& state, const Image& left, const Image& right,
                     const hls::FrameConfig<WINDOW>& cfg, int steps) {
    state.reset();
    int last_step = -1;
    for (int step = 0; step < steps; ++step) {
        const int x = step % left.width;
        const int y = step / left.width;
        const bool in_frame = y < left.height;
        state.step(static_cast<hls::coord_t>(x), static_cast<hls::coord_t>(y),
                   in_frame ? rgb_at(left, x, y) : hls::Rgb{},
                   in_frame ? rgb_at(right, x, y) : hls::Rgb{}, cfg);
        if (state.out_x() == left.width - 1 && state.out_y() == left.height - 1) {
            last_step = step;
        }
    }
    return last_step;
}

TEST(HlsTop, LastResultLeavesAfterTheDocumentedLatency) {
    // hls/README.md: D = (R + 2) * W + R + 9 + N + K pixel steps (the RTL takes 2 more), the sum
    // of the stage latencies 1 + K + (R*W + R + 2) + 2 (W + 2) + 1 measured one by one above,
    // and stage 6's 1 + N.
    constexpr int kWindow = 5;
    constexpr int R = kWindow / 2;
    const int width = 20;
    const int height = 10;
    constexpr int N = 8;
    EXPECT_EQ((hls::pipeline_delay<N, kWindow>(width)),
              1 + (R * width + R + 2) + 2 * (width + 2) + 1 + 1 + N);
    EXPECT_EQ((hls::pipeline_delay<N, kWindow>(width, -5)),
              (hls::pipeline_delay<N, kWindow>(width)) + 5);
    auto rng = seeded(6);
    const auto [left, right] = test::shifted_pair(width, height, 3, 2, 5, rng);
    const MatchParams params{8, kWindow, 2.0, true};
    const auto cfg = hls::frame_config<kWindow>(params, width, height);
    for (const int min_disp : {0, -3, 2}) {
        auto frame_cfg = cfg;
        frame_cfg.min_disp = min_disp;
        const auto state = std::make_unique<hls::pipeline<64, 64, N, kWindow>>();
        const int last_step =
            last_output_step(*state, left, right, frame_cfg,
                             width * height + 3 * hls::pipeline_delay<N, kWindow>(width));
        EXPECT_EQ(last_step + 1, (hls::frame_steps<N, kWindow>(width, height, min_disp)))
            << "min_disp " << min_disp;
    }
}

TEST(HlsTop, BackToBackFramesOfDifferentSizesAndConfigurations) {
    auto rng = seeded(7);
    // One state for every frame, as the static object of a synthesised top: a taller frame
    // after a shorter one, a narrower after a wider, CA on and off, smaller windows.
    const auto state = std::make_unique<hls::pipeline<64, 64, 16, 11>>();
    const std::vector<std::tuple<int, int, MatchParams>> frames = {
        {40, 30, MatchParams{16, 11, fx::kDefaultSigma, true}},
        {25, 45, MatchParams{9, 5, 1.5, true}},
        {64, 14, MatchParams{16, 3, 1.0, false}},
        {40, 30, MatchParams{1, 1, 1.0, true}},
        {40, 30, MatchParams{16, 11, fx::kDefaultSigma, true}},
    };
    for (const auto& [width, height, params] : frames) {
        const auto [left, right] = test::shifted_pair(width, height, 3, 3, 12, rng);
        EXPECT_TRUE(same_map(match(left, right, params), run_top(*state, left, right, params)))
            << width << "x" << height << " ndisp " << params.ndisp << " window " << params.window;
    }
}

TEST(HlsTop, ReportsMisplacedFramingAndClampsTheConfiguration) {
    auto rng = seeded(8);
    const int width = 12;
    const int height = 8;
    const auto [left, right] = test::shifted_pair(width, height, 3, 1, 5, rng);
    const auto state = std::make_unique<hls::pipeline<32, 32, 4, 3>>();
    const MatchParams params{4, 3, 1.0, true};
    auto cfg = hls::frame_config<3>(params, width, height);

    // Framing flags are checked and reported; the data is still processed.
    hls::stream<hls::InputBeat> in;
    hls::stream<hls::OutputBeat> out;
    hls::push_frame(left, right, in);
    std::vector<hls::InputBeat> beats;
    while (!in.empty()) {
        beats.push_back(in.read());
    }
    beats[0].sof = false;
    beats[5].eol = true;
    for (const auto& beat : beats) {
        in.write(beat);
    }
    EXPECT_EQ(hls::stereo_hls_top(in, out, cfg, *state),
              hls::kStatusEolMisplaced | hls::kStatusSofMisplaced);
    ASSERT_EQ(out.size(), static_cast<std::size_t>(width * height));
    // The output framing comes from the coordinates, not from the input flags.
    EXPECT_TRUE(out.read().sof);
    EXPECT_FALSE(out.read().sof);

    // Out-of-range ndisp and radius are clamped to the synthesised maximum, as in the RTL.
    cfg.ndisp = 9;
    cfg.radius = 4;
    hls::stream<hls::OutputBeat> clamped;
    hls::push_frame(left, right, in);
    EXPECT_EQ(hls::stereo_hls_top(in, clamped, cfg, *state), hls::kStatusConfigClamped);
    EXPECT_TRUE(same_map(match(left, right, MatchParams{4, 3, 1.0, true}),
                         hls::collect_frame(clamped, width, height)));
}

// ---- stereo::hls::match against stereo::match ---------------------------------------------

void expect_match(const Image& left, const Image& right, const MatchParams& params,
                  const std::string& what) {
    EXPECT_TRUE(same_map(match(left, right, params), hls::match(left, right, params)))
        << what << ": " << left.width << "x" << left.height << "x" << left.channels << " ndisp "
        << params.ndisp << " window " << params.window << " sigma " << params.sigma
        << (params.use_ca ? " CA" : " no CA");
}

MatchParams with_stage6(MatchParams params, int min_disp, int uniqueness, int lr, bool subpixel) {
    params.min_disp = min_disp;
    params.validation.uniqueness = uniqueness >= 0;
    params.validation.uniqueness_ratio = uniqueness >= 0 ? uniqueness : 10;
    params.validation.left_right = lr >= 0;
    params.validation.lr_tolerance = lr >= 0 ? lr : 1;
    params.validation.subpixel = subpixel;
    return params;
}

// A scene with two surfaces: a random background plane whose disparity grows from `far` at the
// left edge to `far + slant` at the right edge (the right image samples it between pixels,
// linearly interpolated), and a random box in front of it at the integer disparity `near`; plus
// noise, cut from a larger image (no clamped pixels). The background just left of the box is
// hidden in the right image, so stage 6's left-right check rejects it, and the slant makes the
// two images' winners differ by one label here and there (what the tolerance decides); the
// background the box hides in the left image is new texture in the right one; the box edges
// and the noise give the uniqueness test work, the slant the sub-pixel parabola.
io::ImagePair slanted_scene(int width, int height, int far, int slant, int near, int noise,
                            std::mt19937& rng) {
    constexpr int kMargin = 16;
    const Image big = test::random_image(width + 2 * kMargin, height + 2 * kMargin, 3, rng);
    const Image left = io::crop(big, kMargin, kMargin, width, height);
    const int x0 = width / 3;
    const int x1 = 2 * width / 3;
    const int y0 = height / 4;
    const int y1 = 3 * height / 4;
    Image right(width, height, 3);
    std::uniform_int_distribution<int> jitter(-noise, noise);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const bool rows = y >= y0 && y < y1;
            const bool box = rows && x + near >= x0 && x + near < x1;
            const double source = x + far + static_cast<double>(slant) * x / width;
            // Background that the box hides in the left image: new texture.
            const bool hidden = !box && rows && source >= x0 - 1 && source < x1;
            const int sx = static_cast<int>(std::floor(source));
            const double t = source - sx;
            for (int c = 0; c < 3; ++c) {
                const double background = (1 - t) * big.at(kMargin + sx, kMargin + y, c) +
                                          t * big.at(kMargin + sx + 1, kMargin + y, c);
                const int v = hidden ? byte(rng)
                              : box  ? big.at(kMargin + x + near, kMargin + y, c)
                                     : static_cast<int>(std::lround(background));
                right.at(x, y, c) = static_cast<std::uint8_t>(std::clamp(v + jitter(rng), 0, 255));
            }
        }
    }
    return {left, std::move(right)};
}

TEST(HlsMatchValidated, EqualsMatchValidatedOverStage6Parameters) {
    auto rng = seeded(15);
    for (const int shift : {-4, 3}) {
        const auto [left, right] = test::shifted_pair(41, 27, 3, shift, 20, rng);
        struct Combo {
            int ndisp, window, min_disp, uniqueness, lr;
            bool subpixel, ca;
        };
        for (const Combo& c :
             {Combo{16, 5, 0, -1, -1, false, true}, Combo{16, 5, -8, 10, 1, true, true},
              Combo{12, 3, -5, -1, 0, true, false}, Combo{16, 7, 2, 25, -1, true, true},
              Combo{9, 5, -1, 0, 2, false, true}, Combo{3, 3, -2, 50, 1, true, false},
              Combo{1, 5, -3, 10, 0, true, true}, Combo{20, 5, -12, 15, 1, true, true},
              Combo{17, 11, 4, -1, 1, true, true}}) {
            const MatchParams params =
                with_stage6(MatchParams{c.ndisp, c.window, fx::kDefaultSigma, c.ca}, c.min_disp,
                            c.uniqueness, c.lr, c.subpixel);
            const ValidatedDisparity model = match_validated(left, right, params);
            EXPECT_TRUE(same_validated(model, hls::match_validated(left, right, params)))
                << "shift " << shift << " ndisp " << c.ndisp << " window " << c.window
                << " min_disp " << c.min_disp << " uniqueness " << c.uniqueness << " lr " << c.lr
                << (c.subpixel ? " subpixel" : "");
        }
    }
}

// Another cost than AD over signed ranges with every stage-6 step on: the HLS pipeline equals the
// model, all three output fields.
void expect_cost_over_signed_ranges(const std::string& cost, std::uint32_t seed, int lr) {
    auto rng = seeded(seed);
    const auto [left, right] = test::shifted_pair(41, 27, 3, -3, 20, rng);
    for (const int min_disp : {-8, -3, 0, 5}) {
        MatchParams params =
            with_stage6(MatchParams{16, 5, fx::kDefaultSigma, true}, min_disp, 15, lr, true);
        params.cost = cost;
        EXPECT_TRUE(same_validated(match_validated(left, right, params),
                                   hls::match_validated(left, right, params)))
            << cost << " min_disp " << min_disp;
    }
}

// The LCDM cost stage shares the AD stage's signed-range delay lines (cost<..., lcdm_measure>).
TEST(HlsMatchValidated, LcdmCostOverSignedRangesWithStage6) {
    expect_cost_over_signed_ranges("lcdm", 23, 1);
}

// The census stage alone: every code of both images against the model's census::transform, on
// frames of many shapes (one pixel wide or high: the window wraps over several rows) stepped
// back to back through one object with a reset between frames, and flush steps of noise.
TEST(HlsCensus, EveryCodeEqualsTheModelsTransform) {
    auto rng = seeded(31);
    const auto state = std::make_unique<hls::census_transform<64>>();
    std::uniform_int_distribution<int> byte(0, 255);
    const auto noise = [&] {
        return hls::Rgb{static_cast<hls::pixel_t>(byte(rng)), static_cast<hls::pixel_t>(byte(rng)),
                        static_cast<hls::pixel_t>(byte(rng))};
    };
    const auto pack = [](const hls::Rgb& c) {
        return (std::uint32_t{c.r} << 16) | (std::uint32_t{c.g} << 8) | c.b;
    };
    for (const auto& [width, height, channels] :
         {std::tuple{64, 48, 3}, std::tuple{1, 9, 3}, std::tuple{2, 7, 3}, std::tuple{5, 1, 3},
          std::tuple{3, 3, 1}, std::tuple{37, 23, 3}, std::tuple{17, 2, 1}, std::tuple{64, 5, 3}}) {
        const Image left = test::random_image(width, height, channels, rng);
        const Image right = test::random_image(width, height, channels, rng);
        const auto want_left = census::transform(left);
        const auto want_right = census::transform(right);
        state->reset();
        int seen = 0;
        bool all_equal = true;
        for (int step = 0; step < width * height + 3 * width + 4; ++step) {
            const int x = step % width;
            const int y = step / width;
            const bool in_frame = y < height;
            state->step(static_cast<hls::coord_t>(x), static_cast<hls::coord_t>(y),
                        in_frame ? rgb_at(left, x, y) : noise(),
                        in_frame ? rgb_at(right, x, y) : noise(), width, height);
            const int ox = state->out_x();
            const int oy = state->out_y();
            if (oy < 0 || oy >= height) {
                continue;
            }
            const auto index = static_cast<std::size_t>(oy) * width + ox;
            EXPECT_EQ(index, static_cast<std::size_t>(seen)) << "raster order";
            all_equal = all_equal && pack(state->out_left()) == want_left[index] &&
                        pack(state->out_right()) == want_right[index];
            ++seen;
        }
        EXPECT_EQ(seen, width * height) << width << "x" << height;
        EXPECT_TRUE(all_equal) << width << "x" << height << "x" << channels;
    }
}

// The census measure is the model's cost: the Hamming distance of the codes times the weight.
TEST(HlsCensus, MeasureIsTheWeightedHammingDistance) {
    const hls::Rgb a{0xF0, 0x0F, 0x01};
    const hls::Rgb b{0x0F, 0x0F, 0x00};
    EXPECT_EQ(hls::census_measure::distance(a, b), 9 * fx::kCensusWeight);  // 8 + 0 + 1 bits
    EXPECT_EQ(hls::census_measure::distance(a, a), 0);
    const hls::Rgb zero{};
    const hls::Rgb ones{0xFF, 0xFF, 0xFF};
    EXPECT_EQ(hls::census_measure::distance(zero, ones), fx::kCensusBits * fx::kCensusWeight);
}

// A cost plug-in through the HLS pipeline at three windows (CA on where the window is wider
// than a pixel), on a random colour pair.
void expect_cost_equals_model(const std::string& cost, std::mt19937& rng) {
    const auto [left, right] = test::shifted_pair(61, 37, 3, 4, 8, rng);
    for (const int window : {1, 5, 11}) {
        MatchParams params{16, window, fx::kDefaultSigma, window != 1};
        params.cost = cost;
        expect_match(left, right, params, cost);
    }
}

TEST(HlsMatch, CensusCostEqualsModel) {
    auto rng = seeded(32);
    expect_cost_equals_model("census", rng);
    const auto [grey_left, grey_right] = test::shifted_pair(45, 30, 1, 3, 8, rng);
    MatchParams params{16, 5, fx::kDefaultSigma, true};
    params.cost = "census";
    expect_match(grey_left, grey_right, params, "census grey");
}

// The census codes wait in the same delay lines (cost<..., census_measure>).
TEST(HlsMatchValidated, CensusCostOverSignedRangesWithStage6) {
    expect_cost_over_signed_ranges("census", 33, 0);
}

// The census stage's 2 W + 3 steps (2 rows and 2 columns of window, its output register), on
// top of the AD pipeline's latency; and the last result leaves exactly then.
TEST(HlsTop, CensusStageAddsItsLatency) {
    constexpr int kWindow = 5;
    constexpr int N = 8;
    const int width = 20;
    const int height = 10;
    EXPECT_EQ((hls::pipeline_delay<N, kWindow, hls::census_measure>(width)),
              (hls::pipeline_delay<N, kWindow>(width)) + 2 * width + 3);
    auto rng = seeded(34);
    const auto [left, right] = test::shifted_pair(width, height, 3, 2, 5, rng);
    MatchParams params{N, kWindow, 2.0, true};
    params.cost = "census";
    const auto cfg = hls::frame_config<kWindow>(params, width, height);
    const auto state = std::make_unique<
        hls::pipeline<64, 64, N, kWindow, table::kDefaultMaxMinDisp, hls::census_measure>>();
    const int last_step = last_output_step(
        *state, left, right, cfg,
        width * height + 3 * hls::pipeline_delay<N, kWindow>(width) + 2 * width + 3);
    EXPECT_EQ(last_step + 1, (hls::frame_steps<N, kWindow, hls::census_measure>(width, height)));
}

TEST(HlsMatchValidated, TheMatcherRegistryRunsStage6) {
    auto rng = seeded(16);
    const auto [left, right] = test::shifted_pair(33, 21, 3, -2, 15, rng);
    MatchConfig config;
    config.pipeline = with_stage6(MatchParams{8, 5, fx::kDefaultSigma, true}, -4, 10, 1, true);
    MatcherRegistry registry;
    hls::register_matchers(registry);
    const MatchResult result = registry.create("pipeline", "hls", config)->compute(left, right);
    EXPECT_TRUE(same_validated(match_validated(left, right, config.pipeline), result.validated));
    EXPECT_TRUE(same_map(to_label_map(result.validated), result.disparity));
    // The census cost, as test_matcher's registry test runs the model's engines: every stage-6
    // step at work on a slanted scene with an occluding box.
    const auto [scene_left, scene_right] = slanted_scene(72, 56, -1, 3, 6, 6, rng);
    config.pipeline = with_stage6(MatchParams{16, 5, 1.5, true}, -2, 15, 1, true);
    config.pipeline.cost = "census";
    const ValidatedDisparity model = match_validated(scene_left, scene_right, config.pipeline);
    const MatchResult census =
        registry.create("pipeline", "hls", config)->compute(scene_left, scene_right);
    EXPECT_TRUE(same_validated(model, census.validated));
    EXPECT_TRUE(same_map(to_label_map(model), census.disparity));
    const Stage6Counts counts = stage6_counts(model);
    EXPECT_GT(counts.reason[fx::kReasonUniqueness], 0);
    EXPECT_GT(counts.reason[fx::kReasonLeftRight], 0);
    EXPECT_GT(counts.fractional, 0);
}

TEST(HlsMatchValidated, MiddleburyCropsWithStage6) {
    const auto dir = io::data_dir() / "middlebury2003" / "cones";
    if (!std::filesystem::exists(dir / "left.png")) {
        GTEST_SKIP() << "cones not found under " << io::data_dir();
    }
    const auto pair =
        io::crop(io::load_pair(dir / "left.png", dir / "right.png", 2), 40, 40, 96, 64);
    for (const int min_disp : {-6, 0, 5}) {
        const MatchParams params =
            with_stage6(MatchParams{24, 7, fx::kDefaultSigma, true}, min_disp, 15, 1, true);
        EXPECT_TRUE(same_validated(match_validated(pair.left, pair.right, params),
                                   hls::match_validated(pair.left, pair.right, params)))
            << "min_disp " << min_disp;
    }
}

TEST(HlsTop, BackToBackStage6FramesAndMinDispClamp) {
    auto rng = seeded(17);
    const auto state = std::make_unique<hls::pipeline<64, 64, 16, 5>>();
    constexpr int kMax = table::kDefaultMaxMinDisp;
    const std::vector<std::tuple<int, int, MatchParams>> frames = {
        {40, 30, with_stage6(MatchParams{16, 5, fx::kDefaultSigma, true}, -kMax, 10, 1, true)},
        {25, 45, with_stage6(MatchParams{9, 3, 1.5, true}, 3, 20, 0, false)},
        {64, 14, with_stage6(MatchParams{16, 5, 1.0, false}, -2, -1, 2, true)},
        {40, 30, with_stage6(MatchParams{16, 5, fx::kDefaultSigma, true}, 0, -1, -1, false)},
    };
    for (const auto& [width, height, params] : frames) {
        const auto [left, right] = test::shifted_pair(width, height, 3, -1, 12, rng);
        EXPECT_TRUE(same_validated(match_validated(left, right, params),
                                   run_top_validated(*state, left, right, params)))
            << width << "x" << height << " min_disp " << params.min_disp;
    }
    // Beyond +-MAX_MIN_DISP: clamped and flagged, as in the RTL.
    const auto [left, right] = test::shifted_pair(40, 30, 3, -1, 12, rng);
    MatchParams params =
        with_stage6(MatchParams{16, 5, fx::kDefaultSigma, true}, -kMax - 5, 10, 1, true);
    const ValidatedDisparity clamped =
        run_top_validated(*state, left, right, params, hls::kStatusConfigClamped);
    params.min_disp = -kMax;
    EXPECT_TRUE(same_validated(match_validated(left, right, params), clamped));
}

TEST(HlsMatch, SmallRandomImagesOverTheParameters) {
    auto rng = seeded(9);
    const auto [left, right] = test::shifted_pair(37, 23, 3, 3, 8, rng);
    for (const int ndisp : {1, 7, 16, 17, 36}) {
        for (const int window : {1, 3, 5, 11, 13}) {
            for (const bool use_ca : {true, false}) {
                const double sigma = window == 3 ? 0.8 : fx::kDefaultSigma;
                expect_match(left, right, MatchParams{ndisp, window, sigma, use_ca}, "random");
            }
        }
    }
}

TEST(HlsMatch, LcdmCostEqualsModel) {
    auto rng = seeded(22);
    expect_cost_equals_model("lcdm", rng);
    MatchParams params;
    params.cost = "lcdm";
    const Image grey = test::random_image(61, 37, 1, rng);
    EXPECT_THROW((void)hls::match(grey, grey, params), std::invalid_argument);
}

TEST(HlsMatch, OddSizedRandomCrop631x479) {
    auto rng = seeded(10);
    const auto [left, right] = io::crop(test::shifted_pair(640, 480, 3, 5, 6, rng), 7, 1, 631, 479);
    expect_match(left, right, MatchParams{16, 11, fx::kDefaultSigma, true}, "631x479");
    expect_match(left, right, MatchParams{12, 7, 2.0, false}, "631x479");
}

TEST(HlsMatch, GreyImages) {
    auto rng = seeded(11);
    for (const auto& [width, height, ndisp, window] :
         {std::tuple{53, 41, 12, 5}, std::tuple{101, 77, 24, 11}}) {
        const auto [left, right] = test::shifted_pair(width, height, 1, 4, 10, rng);
        expect_match(left, right, MatchParams{ndisp, window, fx::kDefaultSigma, true}, "grey");
        expect_match(left, right, MatchParams{ndisp, window, fx::kDefaultSigma, false}, "grey");
    }
}

TEST(HlsMatch, ConstantAndExtremeImages) {
    for (const auto& [l, r, left, right] : test::constant_pairs(40, 30, 3)) {
        expect_match(left, right, MatchParams{8, 5, 2.0, true}, "constant");
        expect_match(left, right, MatchParams{8, 11, fx::kDefaultSigma, false}, "constant");
    }
    // A 0/255 checkerboard against its inverse: every cost is 0 or the maximum, 765.
    Image left(45, 33, 3);
    Image right(45, 33, 3);
    for (int y = 0; y < left.height; ++y) {
        for (int x = 0; x < left.width; ++x) {
            for (int c = 0; c < 3; ++c) {
                left.at(x, y, c) = (x + y) % 2 == 0 ? 255 : 0;
                right.at(x, y, c) = (x + y) % 2 == 0 ? 0 : 255;
            }
        }
    }
    expect_match(left, right, MatchParams{9, 3, 1.0, true}, "checkerboard");
    expect_match(left, right, MatchParams{16, 11, fx::kDefaultSigma, true}, "checkerboard");
}

TEST(HlsMatch, LargestWindowAndMostLanes) {
    auto rng = seeded(12);
    const auto [left, right] = test::shifted_pair(90, 70, 3, 6, 8, rng);
    expect_match(left, right, MatchParams{20, 31, 6.0, true}, "window 31");
    expect_match(left, right, MatchParams{20, 13, fx::kDefaultSigma, true}, "window 13 of 31");
    const auto [wide_left, wide_right] = test::shifted_pair(300, 40, 3, 40, 8, rng);
    expect_match(wide_left, wide_right, MatchParams{256, 5, 2.0, true}, "256 lanes");
    expect_match(wide_left, wide_right, MatchParams{200, 31, 6.0, false}, "256 lanes, window 31");
}

TEST(HlsMatch, MiddleburyPairs) {
    int found = 0;
    for (const auto& scene : io::middlebury2003_scenes()) {
        const auto data = io::load_scene(io::data_dir(), scene);
        if (!data) {
            continue;
        }
        ++found;
        const io::ImagePair& pair = data->pair;
        std::cout << "[ hls ] " << scene.name << " " << pair.left.width << "x" << pair.left.height
                  << " ndisp " << scene.ndisp << "\n";
        expect_match(pair.left, pair.right,
                     MatchParams{scene.ndisp, fx::kDefaultWindow, fx::kDefaultSigma, true},
                     scene.name);
        if (scene.name == "tsukuba") {
            expect_match(pair.left, pair.right,
                         MatchParams{scene.ndisp, fx::kDefaultWindow, fx::kDefaultSigma, false},
                         scene.name);
        }
    }
    if (found == 0) {
        GTEST_SKIP() << "no Middlebury 2003 pair under " << io::data_dir();
    }
}

TEST(HlsMatch, RejectsWhatTheModelRejects) {
    auto rng = seeded(13);
    const Image left = test::random_image(30, 20, 3, rng);
    const Image right = test::random_image(30, 20, 3, rng);
    for (const auto& params : {MatchParams{8, 4, 2.0, true}, MatchParams{30, 5, 2.0, true},
                               MatchParams{0, 5, 2.0, true}, MatchParams{8, 33, 2.0, true},
                               MatchParams{8, 19, 3.0, true}, MatchParams{8, 5, -1.0, true}}) {
        EXPECT_THROW((void)match(left, right, params), std::invalid_argument);
        EXPECT_THROW((void)hls::match(left, right, params), std::invalid_argument);
    }
    const Image grey = test::random_image(30, 20, 1, rng);
    const Image smaller = test::random_image(29, 20, 3, rng);
    EXPECT_THROW((void)hls::match(left, grey, MatchParams{}), std::invalid_argument);
    EXPECT_THROW((void)hls::match(left, smaller, MatchParams{}), std::invalid_argument);
    // Wider than the compiled variants: the model takes it, the host wrapper refuses.
    const Image wide(hls::kHostMaxWidth + 1, 8, 1);
    EXPECT_THROW((void)hls::match(wide, wide, MatchParams{4, 3, 1.0, false}),
                 std::invalid_argument);
}

TEST(HlsMatch, PicksTheSmallestCoveringVariant) {
    const auto variant = [](int ndisp, int window) {
        const hls::Variant v = hls::variant_for(MatchParams{ndisp, window, 2.0, true});
        return std::pair{v.ndisp, v.window};
    };
    EXPECT_EQ(variant(1, 1), std::pair(16, 11));
    EXPECT_EQ(variant(16, 11), std::pair(16, 11));
    EXPECT_EQ(variant(17, 13), std::pair(64, 31));
    EXPECT_EQ(variant(64, 31), std::pair(64, 31));
    EXPECT_EQ(variant(65, 5), std::pair(256, 11));
    EXPECT_EQ(variant(256, 11), std::pair(256, 11));
}

// ---- the synthesisable top and the stream -------------------------------------------------

// The synthesisable top, frame after frame through its one static state: every configuration
// port reaches the pipeline. Frames with stage 6 off compare the 8-bit labels with stereo::match;
// frames with a signed range and every stage-6 step on compare stage 6's whole output (fixed
// disparity, reason, certainty) with stereo::match_validated. Their ratios and tolerances differ
// from FrameConfig's defaults (0), so a port that is not assigned changes the output.
TEST(HlsSynthTop, FramesBackToBackEqualModel) {
    namespace synth = hls::synth;
    auto rng = seeded(14);
    const auto [full_left, full_right] =
        test::shifted_pair(synth::kWidth, synth::kHeight, 3, 9, 4, rng);
    const auto [scene_left, scene_right] = slanted_scene(96, 64, -4, 4, 6, 6, rng);
    struct Frame {
        Image left;
        Image right;
        MatchParams params;
        bool stage6;
    };
    const std::vector<Frame> frames = {
        {full_left, full_right, MatchParams{synth::kNdisp, synth::kWindow, fx::kDefaultSigma, true},
         false},
        {scene_left, scene_right,
         with_stage6(MatchParams{16, 5, fx::kDefaultSigma, true}, -5, 15, 1, true), true},
        {io::crop(full_left, 3, 5, 100, 60), io::crop(full_right, 3, 5, 100, 60),
         MatchParams{16, 5, 2.0, false}, false},
        {io::crop(scene_left, 2, 3, 90, 58), io::crop(scene_right, 2, 3, 90, 58),
         with_stage6(MatchParams{20, 7, 2.0, true}, -5, 30, 2, true), true},
    };
    for (const auto& [left, right, params, stage6] : frames) {
        SCOPED_TRACE(std::to_string(left.width) + "x" + std::to_string(left.height) + " min_disp " +
                     std::to_string(params.min_disp) +
                     (stage6 ? " with stage 6" : " without stage 6"));
        const auto cfg = hls::frame_config<synth::kWindow>(params, left.width, left.height);
        hls::stream<hls::InputBeat> in;
        hls::stream<hls::OutputBeat> out;
        hls::push_frame(left, right, in);
        EXPECT_EQ(stereo_hls_synth_top(
                      in, out, static_cast<std::uint16_t>(cfg.width),
                      static_cast<std::uint16_t>(cfg.height), static_cast<std::uint16_t>(cfg.ndisp),
                      static_cast<std::uint8_t>(cfg.radius), cfg.kernel, cfg.use_ca,
                      static_cast<std::int16_t>(cfg.min_disp), cfg.uniqueness,
                      static_cast<std::uint8_t>(cfg.uniqueness_ratio), cfg.left_right,
                      static_cast<std::uint8_t>(cfg.lr_tolerance), cfg.subpixel),
                  0);
        if (!stage6) {
            EXPECT_TRUE(same_map(match(left, right, params),
                                 hls::collect_frame(out, left.width, left.height)));
            continue;
        }
        const ValidatedDisparity model = match_validated(left, right, params);
        EXPECT_TRUE(same_validated(model, hls::collect_validated(out, left.width, left.height)));
        // The frame exercises what it configures: negative and fractional disparities, and
        // rejections by the uniqueness test and by the left-right check.
        const Stage6Counts counts = stage6_counts(model);
        std::cout << "[scene] " << left.width << "x" << left.height << ": valid "
                  << counts.reason[fx::kReasonValid] << ", border "
                  << counts.reason[fx::kReasonBorder] << ", uniqueness "
                  << counts.reason[fx::kReasonUniqueness] << ", left-right "
                  << counts.reason[fx::kReasonLeftRight] << ", fractional " << counts.fractional
                  << ", negative " << counts.negative << '\n';
        EXPECT_GT(counts.reason[fx::kReasonUniqueness], 0);
        EXPECT_GT(counts.reason[fx::kReasonLeftRight], 0);
        EXPECT_GT(counts.fractional, 0);
        EXPECT_GT(counts.negative, 0);
    }
}

TEST(HlsStream, IsAFifo) {
    hls::stream<int> fifo("fifo");
    EXPECT_TRUE(fifo.empty());
    EXPECT_FALSE(fifo.full());
    for (int i = 0; i < 5; ++i) {
        fifo.write(i);
    }
    EXPECT_EQ(fifo.size(), 5U);
    int value = -1;
    fifo.read(value);
    EXPECT_EQ(value, 0);
    EXPECT_EQ(fifo.read(), 1);
    EXPECT_TRUE(fifo.read_nb(value));
    EXPECT_EQ(value, 2);
    (void)fifo.read();
    (void)fifo.read();
    EXPECT_TRUE(fifo.empty());
    EXPECT_FALSE(fifo.read_nb(value));
    EXPECT_THROW((void)fifo.read(), std::runtime_error);
}

}  // namespace
}  // namespace stereo
