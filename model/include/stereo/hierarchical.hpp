// Hierarchical 2-D correspondence search for uncalibrated, non-rectified pairs (thesis Sec. 3.3),
// bit-exact like the 1-D pipeline whose stages it reuses. Specified in docs/hierarchical.md.
//
// Three levels (quarter, half, full size). Each level matches a grid of 2-D candidates per pixel:
// candidate (i, j) of pixel (x, y) is the displacement (base_d + i, base_v + j), i.e. the left
// pixel (x, y) against the right pixel (x - d, y + v). The costs of all candidates form a DSI
// over the flattened index k = j * cols + i, aggregated, refined by the CA rules and reduced by
// WTA exactly as in the 1-D pipeline (docs/fixed-point.md).
//   quarter: every displacement of the level's range (a full 2-D search of (D/4) x (V/4));
//   half, full: the 3x3 displacements around the up-scaled (x2) match of the level below.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stereo/constants.hpp"
#include "stereo/image.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/search.hpp"
#include "stereo/validated.hpp"
#include "stereo/validation_params.hpp"

namespace stereo::hierarchical {

// The candidate grid, the CA neighbourhood choice and the per-level winners are the plane
// scheduler's (stereo/search.hpp).
using stereo::CandidateGrid;
using stereo::CaNeighbours;
using LevelMap = stereo::Winners;

struct LevelParams {
    int window = 0;    // odd side of the Gaussian aggregation window
    double sigma = 0;  // Gaussian sigma in the level's pixels
};

// The thesis' windows (9, 15, 23); sigma keeps the ratio of the 1-D default (3 for 11 taps).
constexpr LevelParams default_level(int window) {
    return {window, fx::kDefaultSigma * window / fx::kDefaultWindow};
}

inline constexpr int kLevels = 3;  // quarter, half, full
inline constexpr std::array<int, kLevels> kLevelFactor = {4, 2, 1};
inline constexpr std::array<const char*, kLevels> kLevelNames = {"quarter", "half", "full"};
inline constexpr int kMaxVerticalRange = 252;  // offsets fit an int8 and 128 + v a PNG byte
// The costs the search (and its naive reference) can use are the catalogue's pixel-pair costs
// (AD over RGB, LCDM, the 5x5 census of the luma, each computed on each level's image).

// What the search outputs (docs/hierarchical.md, "Output").
enum class Output {
    full_level,      // the thesis: the full level's 3x3 winners
    vertical_field,  // the full level's offsets, filtered into a field, fix one right-image row per
                     // pixel; a 1-D search over every disparity along it, with stage 6
};

inline constexpr int kMaxFieldRadius = 64;

// How the full level's offsets become the vertical field.
enum class FieldModel {
    mode,   // per pixel, the most frequent valid offset in a window (vertical_field)
    plane,  // one plane v = a + b x + c y for the frame, fitted robustly (vertical_plane)
    mode_with_plane_prior,  // the mode, the plane's offset kept unless clearly outvoted
    radial,  // one plane plus a radial lens term for the frame, fitted robustly (vertical_radial)
    mode_with_radial_prior,  // the mode, the radial model's offset kept unless clearly outvoted
};

// The plane's coefficients in 1/kPlaneOne pixel: v(x, y) = (a + b x + c y) / kPlaneOne.
inline constexpr std::int64_t kPlaneOne = std::int64_t{1} << 16;
struct Plane {
    std::int64_t a = 0;
    std::int64_t b = 0;
    std::int64_t c = 0;
    bool operator==(const Plane&) const = default;
};

// The defaults are the hardware-sized search with the vertical field (docs/hierarchical.md,
// "Output"): V = 16 and windows 9 / 15 / 15, which a streaming core can hold; Params::thesis() is
// the thesis' configuration (V = D, windows 9 / 15 / 23, the full level's winners).
inline constexpr int kDefaultVerticalRange = 16;
inline constexpr Output kDefaultOutput = Output::vertical_field;
inline constexpr FieldModel kDefaultFieldModel = FieldModel::mode_with_radial_prior;

// The field models by the names the CLI, the experiments and the JSON summaries use.
struct FieldModelRow {
    FieldModel model;
    std::string_view name;
    std::string_view summary;
};
inline constexpr std::array<FieldModelRow, 5> kFieldModels = {{
    {FieldModel::mode_with_plane_prior, "prior",
     "the mode, the frame's plane kept unless outvoted"},
    {FieldModel::mode, "mode", "the most frequent offset in a window"},
    {FieldModel::plane, "plane", "one plane v = a + b x + c y for the frame"},
    {FieldModel::radial, "radial", "the plane plus a radial lens term for the frame"},
    {FieldModel::mode_with_radial_prior, "radial-prior",
     "the mode, the frame's radial model kept unless outvoted"},
}};
constexpr std::string_view field_model_name(FieldModel model) {
    for (const FieldModelRow& row : kFieldModels) {
        if (row.model == model) {
            return row.name;
        }
    }
    return {};
}
// The field model of that name; std::nullopt for any other name.
constexpr std::optional<FieldModel> field_model_named(std::string_view name) {
    for (const FieldModelRow& row : kFieldModels) {
        if (row.name == name) {
            return row.model;
        }
    }
    return std::nullopt;
}
inline constexpr int kDefaultFieldRadius = 48;
// The radial field models (vertical_radial): the inlier tolerance of the fits in pixels and the
// gain in explained votes over the plane the lens term must bring to be kept.
inline constexpr double kRadialTolerance = 1.5;
inline constexpr double kDefaultRadialMinGain = 1.03;
inline constexpr std::array<int, 3> kDefaultLevelWindows = {9, 15, 15};
inline constexpr std::array<int, 3> kThesisLevelWindows = {9, 15, 23};
inline constexpr int kMaxLevelWindow = 31;

struct Params {
    int ndisp = fx::kDefaultDisparities;  // D: horizontal labels 0..D-1 at full size
    int vrange = kDefaultVerticalRange;   // V: vertical labels at full size; 0 = same as D
    std::array<LevelParams, kLevels> levels = {default_level(kDefaultLevelWindows[0]),
                                               default_level(kDefaultLevelWindows[1]),
                                               default_level(kDefaultLevelWindows[2])};
    bool use_ca = true;
    CaNeighbours neighbours = CaNeighbours::horizontal;
    std::string cost = "ad";  // a pixel-pair cost of the catalogue
    Output output = kDefaultOutput;
    // Output::vertical_field: the field is the most frequent valid full-level offset in a
    // (2 field_radius + 1)^2 window; the 1-D pass aggregates with `field_level` (the pipeline's
    // 11x11, sigma 3 by default) and CA as the levels, and validates with `validation`.
    FieldModel field_model = kDefaultFieldModel;
    int field_radius = kDefaultFieldRadius;
    int prior_factor = 2;
    // FieldModel::radial and mode_with_radial_prior: the lens term is kept when its model explains
    // at least this many times the votes the plane explains (vertical_radial).
    double radial_min_gain = kDefaultRadialMinGain;
    LevelParams field_level = {fx::kDefaultWindow, fx::kDefaultSigma};
    ValidationParams validation{};

    int vertical_range() const { return vrange == 0 ? ndisp : vrange; }

    // The thesis' search (Sec. 3.3): V = D, windows 9 / 15 / 23, the full level's 3x3 winners.
    static Params thesis() {
        Params params;
        params.vrange = 0;
        params.levels = {default_level(kThesisLevelWindows[0]),
                         default_level(kThesisLevelWindows[1]),
                         default_level(kThesisLevelWindows[2])};
        params.output = Output::full_level;
        return params;
    }
};

// Displacements a level may use, in its own pixels: d in [d_min, d_max], v in [v_min, v_max].
struct SearchRange {
    int d_min = 0;
    int d_max = 0;
    int v_min = 0;
    int v_max = 0;
};

// Range of the level with down-scaling `factor`: D/f horizontal labels 0..D/f-1 and V/f vertical
// labels centred on 0, -(V/f)/2 .. V/f-1-(V/f)/2 (at full size -V/2 .. V/2-1).
SearchRange level_range(const Params& params, int factor);

// Candidates of the quarter level and of the full D x V reference: the whole range for every
// pixel; ties prefer v = 0, then the smallest d.
CandidateGrid full_grid(int width, int height, const SearchRange& range);

// Candidates of a refinement level (half or full) of `width` x `height`: the 3x3 displacements
// around the coarse match, up-scaled x2 from the parent pixel (min(x/2, Wc-1), min(y/2, Hc-1)) and
// clamped per axis into [min+1, max-1] of `range`, so that all nine lie in the range. Ties prefer
// the centre.
CandidateGrid refine_grid(const LevelMap& coarse, int width, int height, const SearchRange& range);

// A pixel is valid when its window and CA neighbourhood (reach = window/2 + 1 with CA) lie inside
// both images at its winning displacement: reach <= x < W - reach, reach <= y < H - reach,
// x - d >= reach and reach <= y + v < H - reach.
bool level_valid(int x, int y, int d, int v, int width, int height, int reach);

// Cost evaluations (DSI cells: one AD of a pixel and a candidate) computed per level.
struct CostCount {
    std::array<std::int64_t, kLevels> level{};  // quarter, half, full (full search: in [2])
    std::int64_t field_pass = 0;                // Output::vertical_field: W H D
    std::int64_t total() const { return level[0] + level[1] + level[2] + field_pass; }
};

// One level: cost (`cost`: AD over RGB or LCDM, fx::kCostOutside outside the right image), Gaussian
// aggregation, [CA rule 1 with `neighbours`, CA rule 2], WTA over the grid with the tie preference,
// validity. Adds the DSI cells it computes to `count`. Streams over candidate rows, so a large full
// grid never holds more than three rows of planes.
LevelMap match_level(const Image& left, const Image& right, const CandidateGrid& grid,
                     const LevelParams& level, bool use_ca, CaNeighbours neighbours,
                     std::int64_t& count, std::string_view cost = "ad");

// Area averaging by an integer factor: floor(W/f) x floor(H/f), each channel the mean of its
// f x f block rounded half up, (sum + f*f/2) / (f*f).
Image downscale_area(const Image& image, int factor);

// Throws std::invalid_argument (one line) unless D and V are multiples of 4 in [8, 256] and
// [8, kMaxVerticalRange], every level's window and sigma are valid and every level image is
// larger than its border and than its horizontal range; with Output::vertical_field also the field
// radius (0..kMaxFieldRadius) and the 1-D pass at full size.
void validate(const Params& params, int width, int height);

struct Result {
    DisparityMap disparity;  // full size, horizontal disparity with the valid flag
    std::vector<std::int8_t>
        vertical;  // full size, vertical offset v (right row = y + v), 0 where invalid
    std::array<LevelMap, kLevels> levels;  // quarter, half, full (full search: only [2])
    CostCount cost_evaluations;
    // Output::vertical_field: the field (every pixel) and stage 6's output of the 1-D pass, of
    // which `disparity` is the 8-bit view; both empty for Output::full_level.
    std::vector<std::int8_t> field;
    ValidatedDisparity validated;
};

// The field lives in the right image's columns: the pass reads it at the right pixel
// (warp_rows), and a roll of the right camera makes the offset a plane in the right image's
// coordinates (v = theta (xr - cx)), not in the left's. So every field model counts a valid
// full-level winner at (x, y) with displacement (d, v) as a vote for v at the right pixel
// (x - d, y); a winner whose right column lies outside the image casts no vote.
inline int right_column(const LevelMap& level, int x, int y) {
    return x - level.disparity[level.index(x, y)];
}

// The vertical field of a full-level map: for every pixel the offset v held by the most votes
// (right_column) of `level`'s valid winners in the (2 radius + 1)^2 window around it (clipped at
// the image), ties to the smaller |v|, then the smaller v; 0 where the window holds no vote.
// With `prior` (one offset per pixel, e.g. plane_field), the prior's offset keeps the pixel unless
// another offset has more than `prior_factor` times its count in the window.
std::vector<std::int8_t> vertical_field(const LevelMap& level, int radius,
                                        const std::vector<std::int8_t>& prior = {},
                                        int prior_factor = 2);

// The robust plane v = a + b xr + c y through the votes (right_column) of `level`'s valid winners:
// starting from the offsets within 2 of the most frequent one, least-squares fits, each over the
// valid winners within 1.5 pixels of the previous plane, until the set of those winners no longer
// changes (at most `max_iterations` fits); the coefficients rounded to 1/kPlaneOne.
Plane vertical_plane(const LevelMap& level, int max_iterations = 16);

// The radial model of the field (docs/hierarchical.md, "Lens distortion"): both images with the
// same radial (division-model) distortion about the image centre (cx, cy) = ((W-1)/2, (H-1)/2)
// move a match's row, to first order, by k (y - cy) d (2 (xr - cx) + d); a shift and a roll
// of the right camera add a plane. So
//     v(xr, y, d) = a + b (xr - cx) + c (y - cy) + k (y - cy) d (2 (xr - cx) + d).
struct RadialModel {
    double a = 0, b = 0, c = 0, k = 0;  // the coefficients of v above
    double cx = 0, cy = 0;              // the centre of the distortion
    double operator()(int xr, int y, int d) const {
        const double x = xr - cx;
        const double yy = y - cy;
        return a + b * x + c * yy + k * yy * d * (2 * x + d);
    }
    bool operator==(const RadialModel&) const = default;
};

// The robust radial model through the votes (right_column: the winner at (x, y) with (d, v) is
// the vote (xr, y, d, v), xr = x - d) of `level`'s valid winners, from the frame's plane (that of
// vertical_plane): least-squares fits of the four coefficients, the first over the votes within
// 2 pixels of the plane, each later one over those within `tolerance` pixels of the previous
// model, until the set of inliers no longer changes (at most `max_iterations` fits; a singular
// fit, from fewer than 4 or degenerate inliers, keeps the last model). The model is returned only
// if it explains at least `min_gain` times as many votes as the plane (a vote is explained when
// the rounded offset, halves up, is its own); otherwise std::nullopt: the frame's field is the
// plane's. Without lens distortion the lens term only fits noise and explains about as many
// votes as the plane (at most 1.6 % more on the 56 undistorted cases of
// docs/results-hierarchical.md); with it, 4-145 % more.
std::optional<RadialModel> vertical_radial(const LevelMap& level, const Plane& plane,
                                           double min_gain = kDefaultRadialMinGain,
                                           double tolerance = kRadialTolerance,
                                           int max_iterations = 16);

// The disparity of every right pixel (xr, y) of a full-level map: the largest disparity among
// the valid winners that vote there (right_column); a right pixel without a vote takes the
// nearest vote of its row (the left one on a tie), a row without votes 0.
std::vector<std::int16_t> right_disparities(const LevelMap& level);

// The field of a radial model: round(model(xr, y, d)) at every right pixel with d its
// right_disparities, halves up, clamped into [v_min, v_max].
std::vector<std::int8_t> radial_field(const RadialModel& model, const LevelMap& level, int v_min,
                                      int v_max);

// The field of a plane: round(v(x, y)), halves up, clamped into [v_min, v_max].
std::vector<std::int8_t> plane_field(const Plane& plane, int width, int height, int v_min,
                                     int v_max);

// The field's offset at the match of a valid pass pixel (x, y) with disparity fixed / 16: the field
// at column x - round(fixed / 16) (halves up), clamped into the image. It is the pixel's vertical
// offset in Result::vertical, and its right row decides the border rule of the pass.
int field_at_match(const std::vector<std::int8_t>& field, int width, int x, int y,
                   std::int16_t fixed);

// The right image as the 1-D pass sees it: pixel (x, y) is the right pixel (x, y + field(x, y)),
// its row clamped into the image. A streaming core reads it from a buffer of V + 1 right rows
// (docs/hierarchical.md, "The pass on a row-warped right image").
Image warp_rows(const Image& right, const std::vector<std::int8_t>& field);

// The 1-D pass of Output::vertical_field: the 1-D pipeline (match_validated: cost, `field_level`
// aggregation, CA as params.use_ca, stage 6 with params.validation) on the left image and
// warp_rows(right, field). Candidate d of pixel (x, y) thus meets the right pixel
// (x - d, y + field(x - d, y)): the field is read at the right pixel's column. A valid pixel whose
// match's row y + field_row(...) lies within the reach of the top or bottom edge is invalid
// (border), like one whose window leaves the image. Adds W H D to `count`.
// The 1-D engine of the pass: stereo::match_validated, or one bit-exact with it (the HLS kernels).
using PassFunction = ValidatedDisparity (*)(const Image&, const Image&, const MatchParams&);
ValidatedDisparity match_along_field(const Image& left, const Image& right,
                                     const std::vector<std::int8_t>& field, const Params& params,
                                     std::int64_t& count,
                                     PassFunction pass = &stereo::match_validated);

// The result of finished levels: the full level's valid winners as the disparity map and the
// vertical offsets.
Result finish(std::array<LevelMap, kLevels> levels, const CostCount& count);
// Output::vertical_field: the validated 1-D pass as the disparity map, the field as the vertical
// offsets of its valid pixels.
Result finish_field(std::array<LevelMap, kLevels> levels, const CostCount& count,
                    std::vector<std::int8_t> field, ValidatedDisparity validated);

// The three levels of the search (quarter, half, full), each refining the one before; adds their
// DSI cells to `count`.
std::array<LevelMap, kLevels> match_levels(const Image& left, const Image& right,
                                           const Params& params, CostCount& count);

// The hierarchical search.
Result match(const Image& left, const Image& right, const Params& params);

// The parts of the search an engine may compute itself, each bit-exact with the model's: the
// three levels and the 1-D pass. The field between them is the model's (the host's, as in the
// hardware core). The HLS engine passes its levels and its 1-D kernels (hls/README.md).
using LevelsFunction = std::array<LevelMap, kLevels> (*)(const Image&, const Image&, const Params&,
                                                         CostCount&);
struct Parts {
    LevelsFunction levels = &match_levels;
    PassFunction pass = &stereo::match_validated;
};
Result match(const Image& left, const Image& right, const Params& params, const Parts& parts);

// Reference for the evaluation: the same cost, aggregation (full-level window), CA and WTA over
// every displacement of the full-size range (D x V candidates per pixel).
Result full_search(const Image& left, const Image& right, const Params& params);

}  // namespace stereo::hierarchical
