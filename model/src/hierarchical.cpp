#include "stereo/hierarchical.hpp"
#include "stereo/catalogue.hpp"
#include "stereo/hierarchical_plane.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "stereo/pipeline.hpp"
#include "stereo/search.hpp"
#include "stereo/stages.hpp"
#include "stereo/stages/validate.hpp"

namespace stereo::hierarchical {
namespace {

std::string level_message(int level, int width, int height, const std::string& what) {
    return std::string(kLevelNames[static_cast<std::size_t>(level)]) + " level (" +
           std::to_string(width) + "x" + std::to_string(height) + "): " + what;
}

}  // namespace

SearchRange level_range(const Params& params, int factor) {
    const int horizontal = params.ndisp / factor;
    const int vertical = params.vertical_range() / factor;
    const int v_min = -(vertical / 2);
    return {0, horizontal - 1, v_min, v_min + vertical - 1};
}

CandidateGrid full_grid(int width, int height, const SearchRange& range) {
    const std::size_t size = static_cast<std::size_t>(width) * height;
    const auto fill = [size](int value) {
        return std::vector<std::int16_t>(size, static_cast<std::int16_t>(value));
    };
    return {width,
            height,
            range.d_max - range.d_min + 1,
            range.v_max - range.v_min + 1,
            fill(range.d_min),
            fill(range.v_min),
            fill(std::clamp(0, range.d_min, range.d_max)),
            fill(std::clamp(0, range.v_min, range.v_max))};
}

CandidateGrid refine_grid(const LevelMap& coarse, int width, int height, const SearchRange& range) {
    const std::size_t size = static_cast<std::size_t>(width) * height;
    CandidateGrid grid{width, height, 3, 3, {}, {}, {}, {}};
    grid.base_d.resize(size);
    grid.base_v.resize(size);
    grid.prefer_d.resize(size);
    grid.prefer_v.resize(size);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t parent =
                coarse.index(std::min(x / 2, coarse.width - 1), std::min(y / 2, coarse.height - 1));
            // Up-scaled x2, then clamped so that the whole 3x3 stays inside the level's range.
            const int d =
                std::clamp(2 * coarse.disparity[parent], range.d_min + 1, range.d_max - 1);
            const int v = std::clamp(2 * coarse.vertical[parent], range.v_min + 1, range.v_max - 1);
            const std::size_t p = static_cast<std::size_t>(y) * width + x;
            grid.base_d[p] = static_cast<std::int16_t>(d - 1);
            grid.base_v[p] = static_cast<std::int16_t>(v - 1);
            grid.prefer_d[p] = static_cast<std::int16_t>(d);
            grid.prefer_v[p] = static_cast<std::int16_t>(v);
        }
    }
    return grid;
}

bool level_valid(int x, int y, int d, int v, int width, int height, int reach) {
    return window_valid(x, y, d, v, width, height, reach);
}

LevelMap match_level(const Image& left, const Image& right, const CandidateGrid& grid,
                     const LevelParams& level, bool use_ca, CaNeighbours neighbours,
                     std::int64_t& count, std::string_view cost_name) {
    check_pair(left, right);
    if (grid.width != left.width || grid.height != left.height || grid.cols < 1 || grid.rows < 1) {
        throw std::invalid_argument("candidate grid does not fit the level image");
    }
    const int width = left.width;
    const int height = left.height;
    const auto cost = make_cost(cost_name);
    const auto aggregator =
        make_gaussian_aggregator(gaussian_kernel(level.window, level.sigma), width, height);
    const auto rule1 = make_ca_rule1(width, height);
    const auto rule2 = make_ca_rule2(width, height);
    const std::array<Refiner*, 2> ca = {rule1.get(), rule2.get()};
    WinnerTakesAll selector(grid);
    count += search(
        cost->prepare(left), cost->prepare(right), grid,
        {*cost, *aggregator, std::span(ca.data(), use_ca ? ca.size() : 0), selector, neighbours});

    LevelMap map = selector.winners();
    const int reach = level.window / 2 + (use_ca ? 1 : 0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t p = map.index(x, y);
            map.valid[p] =
                level_valid(x, y, map.disparity[p], map.vertical[p], width, height, reach) ? 1 : 0;
        }
    }
    return map;
}

namespace {
// A window of the given radius centred at i along a line of the given length, clipped to it:
// at i = 0 adds every position it covers, at each next i adds the one that enters and removes the
// one that leaves (add(position, +1 or -1)).
template <class Add>
void slide_window(int i, int length, int radius, const Add& add) {
    if (i == 0) {
        for (int j = 0; j <= std::min(radius, length - 1); ++j) {
            add(j, 1);
        }
        return;
    }
    if (i + radius < length) {
        add(i + radius, 1);
    }
    if (i - radius - 1 >= 0) {
        add(i - radius - 1, -1);
    }
}
}  // namespace

std::vector<std::int8_t> vertical_field(const LevelMap& level, int radius,
                                        const std::vector<std::int8_t>& prior, int prior_factor) {
    const int width = level.width;
    const int height = level.height;
    const std::size_t size = static_cast<std::size_t>(width) * height;
    std::vector<std::int8_t> field(size, 0);
    if (size == 0) {
        return field;
    }
    int v_min = 0;
    int v_max = 0;
    for (std::size_t p = 0; p < size; ++p) {
        if (level.valid[p] != 0) {
            v_min = std::min<int>(v_min, level.vertical[p]);
            v_max = std::max<int>(v_max, level.vertical[p]);
        }
    }
    const int bins = v_max - v_min + 1;
    // Bins in the order of preference (|v|, then v), so the first maximum found is the winner.
    std::vector<int> order(static_cast<std::size_t>(bins));
    for (int b = 0; b < bins; ++b) {
        order[static_cast<std::size_t>(b)] = b;
    }
    std::sort(order.begin(), order.end(), [v_min](int a, int b) {
        const int va = a + v_min;
        const int vb = b + v_min;
        return std::abs(va) != std::abs(vb) ? std::abs(va) < std::abs(vb) : va < vb;
    });
    // Column histograms over the rows of the window, slid down; the window's histogram slid right.
    std::vector<int> columns(static_cast<std::size_t>(width) * bins, 0);
    // A row's votes go to their right columns.
    const auto add_row = [&](int y, int sign) {
        for (int x = 0; x < width; ++x) {
            const std::size_t p = level.index(x, y);
            const int column = right_column(level, x, y);
            if (level.valid[p] != 0 && column >= 0 && column < width) {
                columns[static_cast<std::size_t>(column) * bins +
                        static_cast<std::size_t>(level.vertical[p] - v_min)] += sign;
            }
        }
    };
    std::vector<int> window(static_cast<std::size_t>(bins));
    const auto add_column = [&](int x, int sign) {
        const int* column = columns.data() + static_cast<std::size_t>(x) * bins;
        for (int b = 0; b < bins; ++b) {
            window[static_cast<std::size_t>(b)] += sign * column[b];
        }
    };
    for (int y = 0; y < height; ++y) {
        slide_window(y, height, radius, add_row);
        std::fill(window.begin(), window.end(), 0);
        for (int x = 0; x < width; ++x) {
            slide_window(x, width, radius, add_column);
            int best = -1;
            int best_count = 0;
            for (const int b : order) {
                if (window[static_cast<std::size_t>(b)] > best_count) {
                    best = b;
                    best_count = window[static_cast<std::size_t>(b)];
                }
            }
            const std::size_t p = level.index(x, y);
            if (!prior.empty()) {
                const int prior_bin = prior[p] - v_min;
                const int prior_count = prior_bin >= 0 && prior_bin < bins
                                            ? window[static_cast<std::size_t>(prior_bin)]
                                            : 0;
                if (best_count <= prior_factor * prior_count || best < 0) {
                    field[p] = prior[p];
                    continue;
                }
            }
            field[p] = static_cast<std::int8_t>(best < 0 ? 0 : best + v_min);
        }
    }
    return field;
}

Plane vertical_plane(const LevelMap& level, int max_iterations) {
    // Every int8 offset: the histogram need not know the level's range.
    constexpr int kLowest = -128;
    constexpr int kHighest = 127;
    // The most frequent valid offset starts the fit (ties: the smaller |v|, then the smaller v).
    PlaneSetting setting{Plane{}, kFirstFitTolerance};
    setting.plane.a =
        histogram_mode(plane_statistics(level, setting, kLowest, kHighest)) * kPlaneOne;
    // The plane is kept in fixed point after every fit, and the inliers are chosen from it in
    // integers, so that the returned plane names exactly the winners of its own last fit.
    std::vector<std::uint8_t> previous;
    for (int iteration = 0; iteration < max_iterations; ++iteration) {
        std::vector<std::uint8_t> inliers(level.valid.size(), 0);
        for (int y = 0; y < level.height; ++y) {
            for (int x = 0; x < level.width; ++x) {
                const std::size_t p = level.index(x, y);
                const int column = right_column(level, x, y);
                inliers[p] = level.valid[p] != 0 && column >= 0 && column < level.width &&
                                     is_plane_inlier(column, y, level.vertical[p], setting)
                                 ? 1
                                 : 0;
            }
        }
        if (inliers == previous) {
            break;  // the same winners as the last fit: the same plane
        }
        previous = std::move(inliers);
        const std::optional<Plane> solved =
            solve_plane(plane_statistics(level, setting, kLowest, kHighest));
        if (!solved) {
            break;  // too few or collinear inliers: keep the last plane
        }
        setting = {*solved, kFitTolerance};
    }
    return setting.plane;
}

std::vector<std::int8_t> plane_field(const Plane& plane, int width, int height, int v_min,
                                     int v_max) {
    std::vector<std::int8_t> field(static_cast<std::size_t>(width) * height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::int64_t value = plane.a + plane.b * x + plane.c * y + kPlaneOne / 2;
            // Floor division: the rounding is halves up for negative values too.
            const std::int64_t rounded =
                value >= 0 ? value / kPlaneOne : -((-value + kPlaneOne - 1) / kPlaneOne);
            field[static_cast<std::size_t>(y) * width + x] =
                static_cast<std::int8_t>(std::clamp<std::int64_t>(rounded, v_min, v_max));
        }
    }
    return field;
}

int field_at_match(const std::vector<std::int8_t>& field, int width, int x, int y,
                   std::int16_t fixed) {
    // round(fixed / 16), halves up, by floor division (fixed may be negative).
    const int shifted = fixed + fx::kSubpixelScale / 2;
    const int disparity = shifted >= 0
                              ? shifted / fx::kSubpixelScale
                              : -((-shifted + fx::kSubpixelScale - 1) / fx::kSubpixelScale);
    const int column = std::clamp(x - disparity, 0, width - 1);
    return field[static_cast<std::size_t>(y) * width + column];
}

Image warp_rows(const Image& right, const std::vector<std::int8_t>& field) {
    if (field.size() != static_cast<std::size_t>(right.width) * right.height) {
        throw std::invalid_argument("the vertical field does not fit the image");
    }
    Image warped(right.width, right.height, right.channels);
    for (int y = 0; y < right.height; ++y) {
        for (int x = 0; x < right.width; ++x) {
            const int row = std::clamp(y + field[static_cast<std::size_t>(y) * right.width + x], 0,
                                       right.height - 1);
            for (int c = 0; c < right.channels; ++c) {
                warped.at(x, y, c) = right.at(x, row, c);
            }
        }
    }
    return warped;
}

namespace {

// The 1-D pipeline's parameters of the pass.
MatchParams pass_params(const Params& params) {
    return {.ndisp = params.ndisp,
            .window = params.field_level.window,
            .sigma = params.field_level.sigma,
            .use_ca = params.use_ca,
            .cost = params.cost,
            .min_disp = 0,
            .validation = params.validation};
}

// The border rule of the pass: a valid pixel whose match's row is within `reach` of the top or
// bottom edge is invalid.
void mark_field_border(ValidatedDisparity& out, const std::vector<std::int8_t>& field, int reach) {
    for (int y = 0; y < out.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
            const std::size_t p = out.index(x, y);
            if (!out.valid(p)) {
                continue;
            }
            const int row = y + field_at_match(field, out.width, x, y, out.fixed[p]);
            if (row < reach || row >= out.height - reach) {
                out.reason[p] = fx::kReasonBorder;
                out.fixed[p] = 0;
            }
        }
    }
}

}  // namespace

ValidatedDisparity match_along_field(const Image& left, const Image& right,
                                     const std::vector<std::int8_t>& field, const Params& params,
                                     std::int64_t& count, PassFunction run_pass) {
    check_pair(left, right);
    const MatchParams pass = pass_params(params);
    ValidatedDisparity out = run_pass(left, warp_rows(right, field), pass);
    count += static_cast<std::int64_t>(left.width) * left.height * params.ndisp;
    mark_field_border(out, field, invalid_border(pass).reach);
    return out;
}

Image downscale_area(const Image& image, int factor) {
    if (factor < 1 || image.width / factor < 1 || image.height / factor < 1) {
        throw std::invalid_argument("cannot downscale a " + std::to_string(image.width) + "x" +
                                    std::to_string(image.height) + " image by " +
                                    std::to_string(factor));
    }
    Image out(image.width / factor, image.height / factor, image.channels);
    const int area = factor * factor;
    std::vector<int> row_sum(static_cast<std::size_t>(out.width) * out.channels);
    for (int y = 0; y < out.height; ++y) {
        std::fill(row_sum.begin(), row_sum.end(), 0);
        for (int dy = 0; dy < factor; ++dy) {
            for (int x = 0; x < out.width * factor; ++x) {
                for (int c = 0; c < image.channels; ++c) {
                    row_sum[static_cast<std::size_t>(x / factor) * image.channels + c] +=
                        image.at(x, y * factor + dy, c);
                }
            }
        }
        for (int x = 0; x < out.width; ++x) {
            for (int c = 0; c < image.channels; ++c) {
                const int sum = row_sum[static_cast<std::size_t>(x) * image.channels + c];
                out.at(x, y, c) = static_cast<std::uint8_t>((sum + area / 2) / area);
            }
        }
    }
    return out;
}

void validate(const Params& params, int width, int height) {
    const auto check_range = [](const char* name, int value, int max) {
        if (value % 4 != 0 || value < 8 || value > max) {
            throw std::invalid_argument(std::string(name) + " must be a multiple of 4 in [8, " +
                                        std::to_string(max) + "] for three levels, got " +
                                        std::to_string(value));
        }
    };
    catalogue::require_cost(params.cost, catalogue::CostUse::pixel_pair, "the hierarchical search");
    check_range("ndisp", params.ndisp, fx::kMaxDisparities);
    if (params.vrange < 0) {
        throw std::invalid_argument("vrange must be >= 0 (0 = same as ndisp), got " +
                                    std::to_string(params.vrange));
    }
    check_range("vrange", params.vertical_range(), kMaxVerticalRange);
    for (int level = 0; level < kLevels; ++level) {
        const int factor = kLevelFactor[static_cast<std::size_t>(level)];
        const LevelParams& lp = params.levels[static_cast<std::size_t>(level)];
        const int level_width = width / factor;
        const int level_height = height / factor;
        try {
            stereo::validate(MatchParams{params.ndisp / factor, lp.window, lp.sigma, params.use_ca},
                             level_width, level_height);
        } catch (const std::invalid_argument& error) {
            throw std::invalid_argument(
                level_message(level, level_width, level_height, error.what()));
        }
    }
    if (params.output == Output::vertical_field) {
        if (params.field_radius < 0 || params.field_radius > kMaxFieldRadius) {
            throw std::invalid_argument("field radius must be in [0, " +
                                        std::to_string(kMaxFieldRadius) + "], got " +
                                        std::to_string(params.field_radius));
        }
        try {
            stereo::validate(MatchParams{params.ndisp, params.field_level.window,
                                         params.field_level.sigma, params.use_ca},
                             width, height);
        } catch (const std::invalid_argument& error) {
            throw std::invalid_argument("1-D pass along the vertical field (" +
                                        std::to_string(width) + "x" + std::to_string(height) +
                                        "): " + error.what());
        }
    }
}

Result finish(std::array<LevelMap, kLevels> levels, const CostCount& count) {
    Result result{{}, {}, std::move(levels), count, {}, {}};
    const LevelMap& full = result.levels[kLevels - 1];
    result.disparity = DisparityMap(full.width, full.height);
    result.vertical.assign(full.valid.size(), 0);
    for (std::size_t p = 0; p < full.valid.size(); ++p) {
        if (full.valid[p] != 0) {
            result.disparity.disparity[p] = static_cast<std::uint8_t>(full.disparity[p]);
            result.disparity.valid[p] = 1;
            result.vertical[p] = static_cast<std::int8_t>(full.vertical[p]);
        }
    }
    return result;
}

Result finish_field(std::array<LevelMap, kLevels> levels, const CostCount& count,
                    std::vector<std::int8_t> field, ValidatedDisparity validated) {
    Result result{to_label_map(validated), std::vector<std::int8_t>(field.size(), 0),
                  std::move(levels),       count,
                  std::move(field),        std::move(validated)};
    const int width = result.validated.width;
    for (int y = 0; y < result.validated.height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t p = result.validated.index(x, y);
            if (result.validated.valid(p)) {
                result.vertical[p] = static_cast<std::int8_t>(
                    field_at_match(result.field, width, x, y, result.validated.fixed[p]));
            }
        }
    }
    return result;
}

std::array<LevelMap, kLevels> match_levels(const Image& left, const Image& right,
                                           const Params& params, CostCount& count) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    std::array<LevelMap, kLevels> levels;
    for (int level = 0; level < kLevels; ++level) {
        const auto l = static_cast<std::size_t>(level);
        const int factor = kLevelFactor[l];
        const Image level_left = factor == 1 ? left : downscale_area(left, factor);
        const Image level_right = factor == 1 ? right : downscale_area(right, factor);
        const SearchRange range = level_range(params, factor);
        const CandidateGrid grid =
            level == 0 ? full_grid(level_left.width, level_left.height, range)
                       : refine_grid(levels[l - 1], level_left.width, level_left.height, range);
        levels[l] = match_level(level_left, level_right, grid, params.levels[l], params.use_ca,
                                params.neighbours, count.level[l], params.cost);
    }
    return levels;
}

Result match(const Image& left, const Image& right, const Params& params) {
    return match(left, right, params, Parts{});
}

Result match(const Image& left, const Image& right, const Params& params, const Parts& parts) {
    CostCount count;
    std::array<LevelMap, kLevels> levels = parts.levels(left, right, params, count);
    if (params.output == Output::full_level) {
        return finish(std::move(levels), count);
    }
    const LevelMap& full = levels[kLevels - 1];
    const SearchRange range = level_range(params, 1);
    std::vector<std::int8_t> field;
    if (params.field_model == FieldModel::mode) {
        field = vertical_field(full, params.field_radius);
    } else if (params.field_model == FieldModel::radial ||
               params.field_model == FieldModel::mode_with_radial_prior) {
        const Plane plane = vertical_plane(full);
        const std::optional<RadialModel> lens =
            vertical_radial(full, plane, params.radial_min_gain);
        field = lens ? radial_field(*lens, full, range.v_min, range.v_max)
                     : plane_field(plane, full.width, full.height, range.v_min, range.v_max);
        if (params.field_model == FieldModel::mode_with_radial_prior) {
            field = vertical_field(full, params.field_radius, field, params.prior_factor);
        }
    } else {
        field =
            plane_field(vertical_plane(full), full.width, full.height, range.v_min, range.v_max);
        if (params.field_model == FieldModel::mode_with_plane_prior) {
            field = vertical_field(full, params.field_radius, field, params.prior_factor);
        }
    }
    ValidatedDisparity validated =
        match_along_field(left, right, field, params, count.field_pass, parts.pass);
    return finish_field(std::move(levels), count, std::move(field), std::move(validated));
}

Result full_search(const Image& left, const Image& right, const Params& params) {
    check_pair(left, right);
    validate(params, left.width, left.height);
    CostCount count;
    std::array<LevelMap, kLevels> levels;
    const CandidateGrid grid = full_grid(left.width, left.height, level_range(params, 1));
    levels[kLevels - 1] = match_level(left, right, grid, params.levels[kLevels - 1], params.use_ca,
                                      params.neighbours, count.level[kLevels - 1], params.cost);
    return finish(std::move(levels), count);
}

}  // namespace stereo::hierarchical
