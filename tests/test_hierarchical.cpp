// The hierarchical 2-D search (thesis Sec. 3.3, docs/hierarchical.md): every level against the
// naive reference bit for bit, hand-computed cases, a synthetic pair with a known 2-D shift field,
// the cost count, and the lens-distortion model of the evaluation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <iostream>
#include <opencv2/imgproc.hpp>
#include <random>

#include "middlebury_crop.hpp"
#include "shifted_pairs.hpp"
#include "stereo/hierarchical.hpp"
#include "stereo/hierarchical_reference.hpp"
#include "stereo/pipeline.hpp"
#include "stereo_io/data_dir.hpp"
#include "stereo_io/distortion.hpp"
#include "stereo_io/io.hpp"
#include "stereo_io/test_compare.hpp"
#include "stereo_io/test_support.hpp"

namespace stereo::hierarchical {
namespace {

using test::same_level;
using test::shifted_2d;

// ---- down-scaling --------------------------------------------------------------------------

// Every level's winners, the disparity and the vertical offsets of `model` equal `reference`'s.
TEST(DownscaleArea, HandComputed) {
    // One grey row pair, factor 2: blocks {1,2,3,4} -> 10/4 = 2.5 -> 3 (half up),
    // {0,0,0,1} -> 0.25 -> 0, {1,1,1,0} -> 0.75 -> 1; the fifth column is dropped (floor).
    Image grey(7, 2, 1);
    grey.pixels = {1, 2, 0, 0, 1, 1, 9,  //
                   3, 4, 0, 1, 1, 0, 9};
    const Image half = downscale_area(grey, 2);
    ASSERT_EQ(half.width, 3);
    ASSERT_EQ(half.height, 1);
    EXPECT_EQ(half.pixels, (std::vector<std::uint8_t>{3, 0, 1}));
    // Factor 4 on a 4x4 colour image: channel sums 16 * 10 + 8 = 168 -> 10.5 -> 11, and 255s.
    Image colour(4, 4, 3);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 4; ++x) {
            colour.at(x, y, 0) = (x + y) % 2 == 0 ? 10 : 11;  // 8 x 10 + 8 x 11 = 168
            colour.at(x, y, 1) = 255;
            colour.at(x, y, 2) = x == 0 && y == 0 ? 8 : 0;  // 8 / 16 = 0.5 -> 1
        }
    }
    const Image quarter = downscale_area(colour, 4);
    EXPECT_EQ(quarter.pixels, (std::vector<std::uint8_t>{11, 255, 1}));
    EXPECT_THROW(downscale_area(grey, 3), std::invalid_argument);  // 2 rows / 3 = 0
}

TEST(DownscaleArea, EqualsNaive) {
    auto rng = test::seeded_rng(1);
    for (const int channels : {1, 3}) {
        const Image image = test::random_image(41, 30, channels, rng);
        for (const int factor : {1, 2, 3, 4}) {
            EXPECT_EQ(naive::downscale_area(image, factor).pixels,
                      downscale_area(image, factor).pixels)
                << "factor " << factor << " channels " << channels;
        }
    }
}

// ---- ranges, grids, validation -------------------------------------------------------------

TEST(LevelRange, HandComputed) {
    Params params = Params::thesis();
    params.ndisp = 32;  // vrange 0: the same as ndisp
    EXPECT_EQ(params.vertical_range(), 32);
    const SearchRange quarter = level_range(params, 4);
    EXPECT_EQ(std::tie(quarter.d_min, quarter.d_max, quarter.v_min, quarter.v_max),
              std::make_tuple(0, 7, -4, 3));
    const SearchRange full = level_range(params, 1);
    EXPECT_EQ(std::tie(full.d_min, full.d_max, full.v_min, full.v_max),
              std::make_tuple(0, 31, -16, 15));
    params.ndisp = 20;
    params.vrange = 20;  // quarter: 5 labels, -2..2; half: 10 labels, -5..4
    const SearchRange q20 = level_range(params, 4);
    EXPECT_EQ(std::tie(q20.d_max, q20.v_min, q20.v_max), std::make_tuple(4, -2, 2));
    const SearchRange h20 = level_range(params, 2);
    EXPECT_EQ(std::tie(h20.d_max, h20.v_min, h20.v_max), std::make_tuple(9, -5, 4));
}

TEST(RefineGrid, UpscalesAndClampsHandComputed) {
    // Coarse 2x2 winners; the level is 5x4 (odd width: column 4 has parent column min(2, 1)).
    LevelMap coarse{2, 2, {0, 3, 2, 7}, {-4, 1, 3, 0}, {1, 1, 1, 1}};
    const SearchRange range{0, 15, -8, 7};  // centre clamped into [1, 14] x [-7, 6]
    const CandidateGrid grid = refine_grid(coarse, 5, 4, range);
    ASSERT_EQ(grid.cols, 3);
    ASSERT_EQ(grid.rows, 3);
    auto centre = [&](int x, int y) {
        const std::size_t p = static_cast<std::size_t>(y) * 5 + x;
        EXPECT_EQ(grid.base_d[p] + 1, grid.prefer_d[p]);
        EXPECT_EQ(grid.base_v[p] + 1, grid.prefer_v[p]);
        return std::pair<int, int>{grid.prefer_d[p], grid.prefer_v[p]};
    };
    EXPECT_EQ(centre(0, 0), std::make_pair(1, -7));  // (0, -8) clamped to (1, -7)
    EXPECT_EQ(centre(1, 1), std::make_pair(1, -7));  // same parent (0, 0)
    EXPECT_EQ(centre(2, 0), std::make_pair(6, 2));   // parent (1, 0): (6, 2)
    EXPECT_EQ(centre(4, 0), std::make_pair(6, 2));   // x / 2 = 2 -> parent column 1
    EXPECT_EQ(centre(0, 3), std::make_pair(4, 6));   // parent (0, 1): (4, 6)
    EXPECT_EQ(centre(4, 3), std::make_pair(14, 0));  // parent (1, 1): (14, 0)
}

TEST(Validate, RefusesWhatThreeLevelsCannotDo) {
    Params params = Params::thesis();
    params.ndisp = 16;
    EXPECT_NO_THROW(validate(params, 128, 96));
    for (const int ndisp : {4, 6, 10, 260}) {
        params.ndisp = ndisp;
        EXPECT_THROW(validate(params, 2000, 1000), std::invalid_argument) << ndisp;
    }
    params.ndisp = 16;
    for (const int vrange : {-4, 4, 18, 256}) {
        params.vrange = vrange;
        EXPECT_THROW(validate(params, 2000, 1000), std::invalid_argument) << vrange;
    }
    params.vrange = 0;
    EXPECT_THROW(validate(params, 40, 96), std::invalid_argument);  // quarter: 10 px, 9x9 + CA
    params.levels[2].window = 24;
    EXPECT_THROW(validate(params, 128, 96), std::invalid_argument);
    params.levels[2] = default_level(23);
    params.levels[0].sigma = 0;
    EXPECT_THROW(validate(params, 128, 96), std::invalid_argument);
}

TEST(DefaultLevels, ThesisWindowsAndScaledSigma) {
    const Params thesis = Params::thesis();
    EXPECT_EQ(thesis.levels[0].window, 9);
    EXPECT_EQ(thesis.levels[1].window, 15);
    EXPECT_EQ(thesis.levels[2].window, 23);
    EXPECT_DOUBLE_EQ(thesis.levels[2].sigma, 3.0 * 23 / 11);
    EXPECT_EQ(thesis.vertical_range(), thesis.ndisp);
    EXPECT_EQ(thesis.output, Output::full_level);
}

// The hardware-sized defaults of issue 45 (docs/hierarchical.md, "Output").
TEST(DefaultLevels, HardwareSizedWithTheVerticalField) {
    const Params params;
    EXPECT_EQ(params.levels[0].window, 9);
    EXPECT_EQ(params.levels[1].window, 15);
    EXPECT_EQ(params.levels[2].window, 15);
    EXPECT_DOUBLE_EQ(params.levels[2].sigma, 3.0 * 15 / 11);
    EXPECT_EQ(params.vertical_range(), 16);
    EXPECT_EQ(params.output, Output::vertical_field);
    EXPECT_EQ(params.field_model, FieldModel::mode_with_radial_prior);
    EXPECT_DOUBLE_EQ(params.radial_min_gain, 1.03);
    EXPECT_EQ(params.field_radius, 48);
    EXPECT_EQ(params.field_level.window, fx::kDefaultWindow);
}

// ---- each level against the naive reference ------------------------------------------------

struct LevelCase {
    int width, height, channels, window;
    bool use_ca;
    CaNeighbours neighbours;
};

class LevelEqualsNaive : public ::testing::TestWithParam<LevelCase> {};

TEST_P(LevelEqualsNaive, FullGridAndRefineGrid) {
    const LevelCase c = GetParam();
    auto rng = test::seeded_rng(c.width * 7 + c.window);
    const Image left = test::random_image(c.width, c.height, c.channels, rng);
    const Image right = shifted_2d(left, 2, -1, 12, rng);
    const LevelParams level = default_level(c.window);

    // A full search (the quarter level and the D x V reference).
    const CandidateGrid full = full_grid(c.width, c.height, SearchRange{0, 5, -2, 1});
    std::int64_t count = 0;
    const LevelMap model_full =
        match_level(left, right, full, level, c.use_ca, c.neighbours, count);
    EXPECT_EQ(count, static_cast<std::int64_t>(c.width) * c.height * 6 * 4);
    EXPECT_TRUE(same_level(naive::match_level(left, right, full, level, c.use_ca, c.neighbours),
                           model_full))
        << "full grid";

    // A refinement level from a random coarse map (random predictions, clamped by the range).
    const int cw = (c.width + 1) / 2;
    const int ch = (c.height + 1) / 2;
    LevelMap coarse{cw, ch, {}, {}, {}};
    std::uniform_int_distribution<int> d_dist(-1, 9);
    std::uniform_int_distribution<int> v_dist(-5, 5);
    for (int i = 0; i < cw * ch; ++i) {
        coarse.disparity.push_back(static_cast<std::int16_t>(d_dist(rng)));
        coarse.vertical.push_back(static_cast<std::int16_t>(v_dist(rng)));
        coarse.valid.push_back(1);
    }
    const CandidateGrid refine = refine_grid(coarse, c.width, c.height, SearchRange{0, 15, -6, 5});
    count = 0;
    const LevelMap model_refine =
        match_level(left, right, refine, level, c.use_ca, c.neighbours, count);
    EXPECT_EQ(count, static_cast<std::int64_t>(c.width) * c.height * 9);
    EXPECT_TRUE(same_level(naive::match_level(left, right, refine, level, c.use_ca, c.neighbours),
                           model_refine))
        << "refine grid";
}

INSTANTIATE_TEST_SUITE_P(
    RandomImages, LevelEqualsNaive,
    ::testing::Values(LevelCase{31, 23, 3, 9, true, CaNeighbours::horizontal},   // quarter
                      LevelCase{40, 33, 3, 15, true, CaNeighbours::horizontal},  // half
                      LevelCase{57, 49, 3, 23, true, CaNeighbours::horizontal},  // full
                      LevelCase{33, 27, 1, 9, true, CaNeighbours::horizontal},   // grey
                      LevelCase{35, 26, 3, 5, false, CaNeighbours::horizontal},  // no CA
                      LevelCase{36, 29, 3, 9, true, CaNeighbours::horizontal_and_vertical}));

TEST(MatchEqualsNaive, RandomPair) {
    auto rng = test::seeded_rng(5);
    const Image left = test::random_image(101, 78, 3, rng);
    const Image right = shifted_2d(left, 6, 3, 15, rng);
    for (const auto neighbours :
         {CaNeighbours::horizontal, CaNeighbours::horizontal_and_vertical}) {
        Params params = Params::thesis();
        params.ndisp = 16;
        params.vrange = 12;
        params.neighbours = neighbours;
        test::match_hierarchical_as_naive(left, right, params);
    }
}

// A Tsukuba crop and the thesis' levels at 16 labels; skipped when the data is absent.
class TsukubaCrop : public ::testing::Test {
  protected:
    void SetUp() override {
        pair = test::middlebury_crop("tsukuba", 150, 100, 104, 84);
        if (!pair) {
            GTEST_SKIP() << "Middlebury tsukuba not found under " << io::data_dir();
        }
        params.ndisp = 16;
    }
    std::optional<io::ImagePair> pair;
    Params params = Params::thesis();
};

TEST_F(TsukubaCrop, MatchEqualsNaive) {
    const Result model = test::match_hierarchical_as_naive(pair->left, pair->right, params);
    // A real scene exercises both axes: most full-size pixels valid, some vertical offsets.
    const auto& full = model.levels[2];
    const auto valid = std::count(full.valid.begin(), full.valid.end(), 1);
    const auto moved =
        std::count_if(model.vertical.begin(), model.vertical.end(), [](auto v) { return v != 0; });
    std::cout << "[fixture] tsukuba crop: valid " << valid << ", v != 0 " << moved << " of "
              << full.valid.size() << '\n';
    EXPECT_GT(valid, static_cast<std::ptrdiff_t>(full.valid.size() / 2));
    EXPECT_GT(moved, 0);
}

// ---- the vertical field and the validated 1-D pass (Output::vertical_field) -----------------

// Every field model, validation on and off, against the naive reference on a pair whose right
// image is moved by 3 rows and 6 columns (with noise), and on a random pair (no structure at all).
TEST(VerticalFieldEqualsNaive, EveryFieldModel) {
    // The moved pair comes from a fixed seed: how much of its field holds the 3 rows (checked
    // below) is a property of one image, and some random images give less (with
    // STEREO_SEED=3856857690 the plane held 67 %, below the 95 % asked). The unrelated pair
    // follows STEREO_SEED.
    std::mt19937 fixed(21);
    const Image left = test::random_image(84, 64, 3, fixed);
    const Image moved = shifted_2d(left, 6, 3, 15, fixed);
    auto rng = test::seeded_rng(21);
    const Image unrelated = test::random_image(84, 64, 3, rng);
    struct Case {
        const Image* right;
        FieldModel model;
        bool validate;
    };
    for (const auto& c :
         {Case{&moved, FieldModel::mode, true}, Case{&moved, FieldModel::plane, true},
          Case{&moved, FieldModel::mode_with_plane_prior, false},
          Case{&moved, FieldModel::mode_with_plane_prior, true},
          Case{&moved, FieldModel::mode_with_radial_prior, true},
          Case{&unrelated, FieldModel::mode_with_plane_prior, true},
          Case{&unrelated, FieldModel::mode_with_radial_prior, true}}) {
        Params params = Params::thesis();
        params.ndisp = 16;
        params.vrange = 12;
        params.cost = "census";
        params.output = Output::vertical_field;
        params.field_model = c.model;
        params.field_radius = 9;
        params.field_level = {7, 2.0};
        if (c.validate) {
            params.validation = {true, 0, true, 1, true};
        }
        const Result result = test::match_hierarchical_as_naive(left, *c.right, params);
        ASSERT_EQ(result.field.size(), result.disparity.valid.size());
        if (c.right == &moved) {
            // The field holds the 3 rows: everywhere with the plane; with the mode wherever the
            // window saw enough right winners (not near the corners of this small random pair).
            const auto three = std::count(result.field.begin(), result.field.end(), 3);
            const auto size = static_cast<std::ptrdiff_t>(result.field.size());
            const std::ptrdiff_t least = c.model == FieldModel::plane  ? size * 19 / 20
                                         : c.model == FieldModel::mode ? size * 3 / 5
                                                                       : size * 3 / 4;
            EXPECT_GE(three, least) << static_cast<int>(c.model);
        }
    }
}

TEST_F(TsukubaCrop, VerticalFieldWithAdEqualsNaive) {
    params.output = Output::vertical_field;
    params.validation = {true, 6, true, 0, true};
    test::match_hierarchical_as_naive(pair->left, pair->right, params);
}

// warp_rows by hand: a 3x4 grey image whose pixel (x, y) is 10 y + x, a field of -1, 0, +2 by
// column and one row +5; rows outside the image are clamped to the nearest one.
TEST(WarpRows, HandComputed) {
    Image right(3, 4, 1);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 3; ++x) {
            right.at(x, y, 0) = static_cast<std::uint8_t>(10 * y + x);
        }
    }
    const std::vector<std::int8_t> field = {-1, 0, 2,  //
                                            -1, 0, 2,  //
                                            5,  5, 5,  //
                                            -1, 0, 2};
    const Image warped = warp_rows(right, field);
    const std::vector<int> expected = {0,  1,  22,   // row 0: rows -1 (clamped to 0), 0, 2
                                       0,  11, 32,   // row 1: rows 0, 1, 3
                                       30, 31, 32,   // row 2: row 7, clamped to 3
                                       20, 31, 32};  // row 3: rows 2, 3, 5 (clamped to 3)
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 3; ++x) {
            EXPECT_EQ(warped.at(x, y, 0), expected[static_cast<std::size_t>(y) * 3 + x])
                << x << "," << y;
        }
    }
    EXPECT_THROW(warp_rows(right, std::vector<std::int8_t>(11, 0)), std::invalid_argument);
}

// The votes sit at the right columns: a 6x1 map, radius 0, so the field at a column is the vote
// cast there. (3, 0) with d = 3, v = 2 votes at 0; (4, 0) with d = 1, v = -1 at 3; (1, 0) with
// d = 2 points outside the image and casts none; (5, 0) is invalid.
TEST(VerticalField, VotesSitAtTheRightColumn) {
    const LevelMap level{6, 1, {0, 2, 0, 3, 1, 0}, {0, 5, 0, 2, -1, 4}, {0, 1, 0, 1, 1, 0}};
    EXPECT_EQ(vertical_field(level, 0), (std::vector<std::int8_t>{2, 0, 0, -1, 0, 0}));
    EXPECT_EQ(naive::vertical_field(level, 0, {}, 2),
              (std::vector<std::int8_t>{2, 0, 0, -1, 0, 0}));
}

// The mode by hand: a 5x3 map, radius 1, ties to the smaller |v| then the smaller v, invalid
// winners not counted, a prior kept unless outvoted more than twice.
TEST(VerticalField, HandComputed) {
    LevelMap level{5, 3, std::vector<std::int16_t>(15, 0), {}, {}};
    level.vertical = {2, 2, -1, 1,  1,  //
                      2, 0, -1, 1,  1,  //
                      0, 0, 5,  -1, -1};
    level.valid = {1, 1, 1, 1, 1,  //
                   1, 1, 1, 1, 1,  //
                   1, 1, 0, 1, 1};
    // (0,0): window x 0..1, y 0..1 holds 2,2,2,0 -> 2. (2,1): x 1..3, y 0..2 holds 2,-1,1,0,-1,1,
    // 0,-1 (the 5 is invalid): -1 three times -> -1. (4,2): x 3..4, y 1..2: 1,1,-1,-1 -> tie of
    // 1 and -1 at |v| = 1 -> -1. (1,2): x 0..2, y 1..2: 2,0,-1,0,0 -> 0.
    const auto field = vertical_field(level, 1);
    EXPECT_EQ(field[0], 2);
    EXPECT_EQ(field[1 * 5 + 2], -1);
    EXPECT_EQ(field[2 * 5 + 4], -1);
    EXPECT_EQ(field[2 * 5 + 1], 0);
    EXPECT_EQ(field, naive::vertical_field(level, 1, {}, 0));
    // Prior 1 everywhere, factor 2: at (2,1) 1 has count 2 and -1 count 3 <= 4: the prior stays;
    // at (0,0) 1 has count 0 and 2 has 3 > 0: the mode wins.
    const std::vector<std::int8_t> prior(15, 1);
    const auto with_prior = vertical_field(level, 1, prior, 2);
    EXPECT_EQ(with_prior[1 * 5 + 2], 1);
    EXPECT_EQ(with_prior[0], 2);
    EXPECT_EQ(with_prior, naive::vertical_field(level, 1, prior, 2));
}

// The plane fit: winners on round(1.5 + 0.02 x - 0.01 y) with 20 % outliers; the fit must satisfy
// the normal equations of its final inliers (the least-squares property, checked here in long
// double independently of the fit's own arithmetic) and lie within a rounding of the true plane.
TEST(VerticalPlane, LeastSquaresOverItsInliers) {
    const int width = 120;
    const int height = 90;
    LevelMap level{width, height, std::vector<std::int16_t>(width * height, 0),
                   std::vector<std::int16_t>(width * height),
                   std::vector<std::uint8_t>(width * height, 1)};
    auto rng = test::seeded_rng(3);
    std::uniform_int_distribution<int> percent(0, 99);
    std::uniform_int_distribution<int> wild(-8, 7);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const double truth = 1.5 + 0.02 * x - 0.01 * y;
            level.vertical[level.index(x, y)] = static_cast<std::int16_t>(
                percent(rng) < 20 ? wild(rng) : static_cast<int>(std::lround(truth)));
        }
    }
    const Plane plane = vertical_plane(level);
    const auto value = [&](int x, int y) {
        return (static_cast<long double>(plane.a) + static_cast<long double>(plane.b) * x +
                static_cast<long double>(plane.c) * y) /
               kPlaneOne;
    };
    EXPECT_NEAR(static_cast<double>(plane.b) / kPlaneOne, 0.02, 0.002);
    EXPECT_NEAR(static_cast<double>(plane.c) / kPlaneOne, -0.01, 0.002);
    EXPECT_NEAR(static_cast<double>(value(60, 45)), 1.5 + 1.2 - 0.45, 0.05);
    // The plane is the least-squares plane of its own inliers (the valid winners within 1.5 of
    // it, found here in exact integers as the fit states): the gradient of the squared residuals
    // over them is zero but for the rounding of the coefficients to 1/65536, which moves each
    // residual by at most (1 + x + y) / 2 / 65536.
    long double gradient[3] = {0, 0, 0};
    long double bound[3] = {0, 0, 0};
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::int64_t v = level.vertical[level.index(x, y)];
            if (std::abs(v * kPlaneOne - (plane.a + plane.b * x + plane.c * y)) >
                3 * kPlaneOne / 2) {
                continue;
            }
            const long double residual = static_cast<long double>(v) - value(x, y);
            const long double shift = (1.0L + x + y) / 2 / kPlaneOne;
            const long double row[3] = {1, static_cast<long double>(x),
                                        static_cast<long double>(y)};
            for (int i = 0; i < 3; ++i) {
                gradient[i] += row[i] * residual;
                bound[i] += row[i] * shift;
            }
        }
    }
    for (int i = 0; i < 3; ++i) {
        EXPECT_LE(std::fabs(static_cast<double>(gradient[i])), static_cast<double>(bound[i]) + 1e-6)
            << i;
    }
}

TEST(PlaneField, RoundsHalvesUpAndClamps) {
    // v = (a + b x) / 65536 with a = -0.5 and b = 0.25: x = 0 -> -0.5 -> 0 (halves up);
    // x = 1 -> -0.25 -> 0; x = 2 -> 0; x = 4 -> 0.5 -> 1; x = 30 -> 7 clamped to 3.
    const Plane plane{-kPlaneOne / 2, kPlaneOne / 4, 0};
    const auto field = plane_field(plane, 31, 1, -4, 3);
    EXPECT_EQ(field[0], 0);
    EXPECT_EQ(field[1], 0);
    EXPECT_EQ(field[4], 1);
    EXPECT_EQ(field[6], 1);
    EXPECT_EQ(field[30], 3);
    const Plane down{-3 * kPlaneOne / 2, 0, 0};  // -1.5 -> -1
    EXPECT_EQ(plane_field(down, 1, 1, -4, 3)[0], -1);
    EXPECT_EQ(field, naive::plane_field(plane, 31, 1, -4, 3));
}

TEST(Validate, RefusesAnImpossibleField) {
    Params params = Params::thesis();
    params.ndisp = 16;
    params.output = Output::vertical_field;
    params.field_radius = kMaxFieldRadius + 1;
    EXPECT_THROW(validate(params, 200, 150), std::invalid_argument);
    params.field_radius = 8;
    params.field_level = {61, 3.0};  // the 1-D pass's window does not fit 60 rows
    EXPECT_THROW(validate(params, 200, 60), std::invalid_argument);
    params.field_level = {11, 3.0};
    EXPECT_NO_THROW(validate(params, 200, 150));
}

// ---- hand-checked cases --------------------------------------------------------------------

TEST(MatchLevel, ConstantImagesTieToThePreferredDisplacement) {
    // Every candidate costs the same inside the image, so the tie rule decides: the full grid
    // prefers (0, 0), a refinement grid its centre. Outside-image candidates cost more.
    Image left(30, 30, 3);
    Image right(30, 30, 3);
    std::fill(left.pixels.begin(), left.pixels.end(), std::uint8_t{100});
    std::fill(right.pixels.begin(), right.pixels.end(), std::uint8_t{90});
    std::int64_t count = 0;
    const LevelMap full = match_level(left, right, full_grid(30, 30, SearchRange{0, 3, -2, 1}),
                                      default_level(5), true, CaNeighbours::horizontal, count);
    EXPECT_EQ(full.disparity[full.index(15, 15)], 0);
    EXPECT_EQ(full.vertical[full.index(15, 15)], 0);
    EXPECT_EQ(full.valid[full.index(15, 15)], 1);
    EXPECT_EQ(full.valid[full.index(2, 15)], 0);  // reach 3 > x
    LevelMap coarse{15, 15, std::vector<std::int16_t>(225, 2), std::vector<std::int16_t>(225, -1),
                    std::vector<std::uint8_t>(225, 1)};
    const LevelMap refined =
        match_level(left, right, refine_grid(coarse, 30, 30, SearchRange{0, 7, -4, 3}),
                    default_level(5), true, CaNeighbours::horizontal, count);
    EXPECT_EQ(refined.disparity[refined.index(15, 15)], 4);
    EXPECT_EQ(refined.vertical[refined.index(15, 15)], -2);
}

TEST(MatchLevel, OnePixelWindowFindsTheExactDisplacement) {
    // Window 1 without CA: the aggregate is the pixel's AD cost * 16, so a pixel-exact 2-D copy
    // (right(x', y') = left(x' + 1, y' - 2)) is found wherever both pixels exist.
    auto rng = test::seeded_rng(9);
    const Image left = test::random_image(12, 10, 3, rng);
    const Image right = shifted_2d(left, 1, 2, 0, rng);
    std::int64_t count = 0;
    const LevelMap map = match_level(left, right, full_grid(12, 10, SearchRange{0, 3, -3, 3}),
                                     LevelParams{1, 1.0}, false, CaNeighbours::horizontal, count);
    for (int y = 0; y + 2 < 10; ++y) {
        for (int x = 1; x < 12; ++x) {
            EXPECT_EQ(map.disparity[map.index(x, y)], 1) << x << "," << y;
            EXPECT_EQ(map.vertical[map.index(x, y)], 2) << x << "," << y;
            EXPECT_EQ(map.valid[map.index(x, y)], 1);  // reach 0
        }
    }
}

// ---- a synthetic pair with a known 2-D shift field -----------------------------------------

// The left image is random texture; the right image is built so that left (x, y) appears at
// right (x - d(x, y), y + v(x, y)). All shifts and band edges are multiples of 4, so the
// quarter- and half-size pairs are exact shifted copies too. A pixel is expected exactly when, at
// every level, its window (reach = w + 1, in full-size pixels) lies in one band of the field and
// inside both images at the true displacement: the true candidate then costs 0 and every other
// one costs more (random texture).
struct ShiftField {
    int width, height;
    std::function<int(int, int)> d;  // of the left pixel
    std::function<int(int, int)> v;
    std::function<int(int, int)> band;
};

void expect_field_recovered(const ShiftField& field, const Params& params) {
    auto rng = test::seeded_rng(11);
    const Image left = test::random_image(field.width, field.height, 3, rng);
    Image right = test::random_image(field.width, field.height, 3, rng);
    for (int y = 0; y < field.height; ++y) {
        for (int x = 0; x < field.width; ++x) {
            const int xr = x - field.d(x, y);
            const int yr = y + field.v(x, y);
            if (xr >= 0 && yr >= 0 && yr < field.height) {
                for (int c = 0; c < 3; ++c) {
                    right.at(xr, yr, c) = left.at(x, y, c);
                }
            }
        }
    }
    const Result result = match(left, right, params);

    int expected_pixels = 0;
    for (int y = 0; y < field.height; ++y) {
        for (int x = 0; x < field.width; ++x) {
            bool expected = true;
            for (int l = 0; l < kLevels; ++l) {
                const int f = kLevelFactor[static_cast<std::size_t>(l)];
                const int reach = params.levels[static_cast<std::size_t>(l)].window / 2 + 1;
                const int xl = x / f;
                const int yl = y / f;
                const int x0 = f * (xl - reach);  // the window's full-size footprint
                const int x1 = f * (xl + reach) + f - 1;
                const int y0 = f * (yl - reach);
                const int y1 = f * (yl + reach) + f - 1;
                if (x0 < 0 || y0 < 0 || x1 >= field.width || y1 >= field.height ||
                    field.band(x0, y0) != field.band(x1, y1) ||
                    field.band(x0, y1) != field.band(x1, y0)) {
                    expected = false;
                    break;
                }
                const int d = field.d(x, y) / f;
                const int v = field.v(x, y) / f;
                if (xl - d - reach < 0 || yl + v - reach < 0 ||
                    yl + v + reach >= field.height / f) {
                    expected = false;
                    break;
                }
            }
            if (!expected) {
                continue;
            }
            ++expected_pixels;
            const std::size_t p = result.disparity.index(x, y);
            ASSERT_EQ(result.disparity.valid[p], 1) << x << "," << y;
            ASSERT_EQ(result.disparity.disparity[p], field.d(x, y)) << x << "," << y;
            ASSERT_EQ(result.vertical[p], field.v(x, y)) << x << "," << y;
        }
    }
    EXPECT_GT(expected_pixels, field.width * field.height / 8);
}

TEST(ShiftField, VerticalTearRecoveredExactly) {
    // d = 8 everywhere; v = +4 left of column 96, -4 from there on.
    const ShiftField field{192, 144, [](int, int) { return 8; },
                           [](int x, int) { return x < 96 ? 4 : -4; },
                           [](int x, int) { return x < 96 ? 0 : 1; }};
    Params params = Params::thesis();
    params.ndisp = 16;
    params.vrange = 16;
    expect_field_recovered(field, params);
}

TEST(ShiftField, DisparityStepRecoveredExactly) {
    // v = 4 everywhere; d = 8 above row 72, 16 from there on.
    const ShiftField field{192, 144, [](int, int y) { return y < 72 ? 8 : 16; },
                           [](int, int) { return 4; }, [](int, int y) { return y < 72 ? 0 : 1; }};
    Params params = Params::thesis();
    params.ndisp = 24;
    params.vrange = 16;
    expect_field_recovered(field, params);
}

// ---- cost count and the full D x V reference -----------------------------------------------

TEST(CostCount, LevelsAndFullSearch) {
    auto rng = test::seeded_rng(13);
    const Image left = test::random_image(130, 98, 3, rng);  // quarter 32x24, half 65x49
    const Image right = shifted_2d(left, 4, 0, 5, rng);
    Params params = Params::thesis();
    params.ndisp = 32;
    params.vrange = 16;
    const Result hierarchical = match(left, right, params);
    EXPECT_EQ(hierarchical.cost_evaluations.level[0], 32 * 24 * 8 * 4);
    EXPECT_EQ(hierarchical.cost_evaluations.level[1], 65 * 49 * 9);
    EXPECT_EQ(hierarchical.cost_evaluations.level[2], 130 * 98 * 9);
    const Result full = full_search(left, right, params);
    EXPECT_EQ(full.cost_evaluations.total(), 130 * 98 * 32 * 16);
}

TEST(FullSearch, EqualsNaiveLevelOverTheWholeRange) {
    // The full search is one full-size level over the whole range (small window to keep the
    // naive direct sums fast).
    auto rng = test::seeded_rng(17);
    const Image left = test::random_image(72, 60, 3, rng);
    const Image right = shifted_2d(left, 5, -3, 10, rng);
    Params params = Params::thesis();
    params.ndisp = 12;
    params.vrange = 8;
    params.levels = {default_level(3), default_level(5), default_level(7)};
    const Result full = full_search(left, right, params);
    const LevelMap reference =
        naive::match_level(left, right, full_grid(72, 60, level_range(params, 1)), params.levels[2],
                           true, CaNeighbours::horizontal);
    EXPECT_TRUE(same_level(reference, full.levels[2]));
    // Where the window is inside both images, the true displacement wins.
    EXPECT_EQ(full.disparity.disparity[full.disparity.index(40, 30)], 5);
    EXPECT_EQ(full.vertical[full.disparity.index(40, 30)], -3);
}

}  // namespace
}  // namespace stereo::hierarchical

// ---- the lens-distortion model of the evaluation (app/, OpenCV) ----------------------------

namespace stereo::io {
namespace {

TEST(Distortion, DefinitionOfPercentHandChecked) {
    // 10 % barrel on a 400x300 image: half-diagonal 250. A point at the undistorted corner
    // (radius 250) is drawn at radius 250 * 0.9 = 225, i.e. 25 px (10 % of 250) closer.
    const RadialDistortion lens(400, 300, 10.0);
    EXPECT_DOUBLE_EQ(lens.half_diagonal(), 250.0);
    const cv::Point2d corner_u(399.5, 299.5);  // pixel-centre coordinates: centre (199.5, 149.5)
    const cv::Point2d corner_d = lens.distort(corner_u);
    EXPECT_NEAR(corner_d.x, 199.5 + 200 * 0.9, 1e-9);
    EXPECT_NEAR(corner_d.y, 149.5 + 150 * 0.9, 1e-9);
    EXPECT_NEAR(std::hypot(corner_d.x - corner_u.x, corner_d.y - corner_u.y), 25.0, 1e-9);
    // The centre does not move; 0 % is the identity.
    EXPECT_NEAR(lens.distort({199.5, 149.5}).x, 199.5, 1e-12);
    const RadialDistortion none(400, 300, 0.0);
    EXPECT_NEAR(none.distort({10, 20}).y, 20.0, 1e-12);
    // Pincushion (negative percent) moves the corner out by the same fraction.
    EXPECT_NEAR(RadialDistortion(400, 300, -10.0).distort(corner_u).x, 199.5 + 200 * 1.1, 1e-9);
}

TEST(Distortion, ForwardInverseRoundTrip) {
    for (const double percent : {2.5, 10.0, 15.0, -7.5}) {
        const RadialDistortion lens(384, 288, percent);
        for (int y = 0; y < 288; y += 17) {
            for (int x = 0; x < 384; x += 13) {
                const cv::Point2d p(x, y);
                const cv::Point2d back = lens.undistort(lens.distort(p));
                EXPECT_NEAR(back.x, p.x, 1e-9) << percent;
                EXPECT_NEAR(back.y, p.y, 1e-9) << percent;
            }
        }
    }
}

TEST(Distortion, RemapMovesAPointWhereTheModelSays) {
    // A white 3x3 patch near the corner lands where distort() puts its centre.
    cv::Mat image(120, 160, CV_8UC1, cv::Scalar(0));
    image(cv::Rect(139, 99, 3, 3)).setTo(255);
    const RadialDistortion lens(160, 120, 10.0);
    const cv::Mat warped = distort_image(image, lens, cv::INTER_NEAREST);
    const cv::Point2d target = lens.distort({140, 100});
    EXPECT_EQ(warped.at<std::uint8_t>(static_cast<int>(std::lround(target.y)),
                                      static_cast<int>(std::lround(target.x))),
              255);
}

}  // namespace
}  // namespace stereo::io
