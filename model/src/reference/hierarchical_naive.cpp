// The naive hierarchical search: written again from docs/hierarchical.md, loop by loop, so
// that tests/test_hierarchical.cpp can hold the streaming model against it bit for bit.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "stereo/catalogue.hpp"
#include "stereo/dsi.hpp"
#include "stereo/edge_frontend.hpp"
#include "stereo/hierarchical_reference.hpp"
#include "stereo/pipeline.hpp"
#include "stereo/reference.hpp"
#include "stereo/stages/lcdm.hpp"

namespace stereo::hierarchical::naive {
namespace {

// A whole volume, [k][y][x], as plain integers.
struct Volume {
    int width;
    int height;
    int planes;
    std::vector<std::int64_t> cells;

    Volume(int w, int h, int n)
        : width(w), height(h), planes(n), cells(static_cast<std::size_t>(w) * h * n, 0) {}
    std::int64_t& at(int x, int y, int k) {
        return cells[(static_cast<std::size_t>(k) * height + y) * width + x];
    }
    std::int64_t at(int x, int y, int k) const {
        return cells[(static_cast<std::size_t>(k) * height + y) * width + x];
    }
    bool inside(int x, int y) const { return x >= 0 && x < width && y >= 0 && y < height; }
};

bool agree(std::int64_t neighbour, std::int64_t centre) {
    return 2 * std::abs(neighbour - centre) < centre;
}

// The images a level's cost reads: the pixels, and for census their naive luma.
struct CostImages {
    const Image& left;
    const Image& right;
    catalogue::Cost cost;  // a pixel-pair cost
    Image left_grey;
    Image right_grey;
};

// The cost of left pixel (x, y) against right pixel (x - d, y + v).
std::int64_t pixel_cost(const CostImages& images, int x, int y, int d, int v) {
    const Image& left = images.left;
    const Image& right = images.right;
    const int xr = x - d;
    const int yr = y + v;
    if (xr < 0 || xr >= right.width || yr < 0 || yr >= right.height) {
        return fx::kCostOutside;
    }
    switch (images.cost) {
        case catalogue::Cost::lcdm:
            return lcdm::naive::pixel_cost(left, x, y, right, xr, yr, lcdm::kDarkFloor);
        case catalogue::Cost::census:
            return census::naive::pixel_cost(images.left_grey, x, y, images.right_grey, xr, yr);
        case catalogue::Cost::ad:
        case catalogue::Cost::zncc:  // refused by match_level
            break;
    }
    std::int64_t sum = 0;
    for (int c = 0; c < fx::kChannels; ++c) {
        const int lc = left.channels == 1 ? 0 : c;  // grey is matched as (g, g, g)
        sum += std::abs(left.at(x, y, lc) - right.at(xr, yr, lc));
    }
    return sum;
}

}  // namespace

Image downscale_area(const Image& image, int factor) {
    Image out(image.width / factor, image.height / factor, image.channels);
    for (int y = 0; y < out.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
            for (int c = 0; c < image.channels; ++c) {
                int sum = 0;
                for (int j = 0; j < factor; ++j) {
                    for (int i = 0; i < factor; ++i) {
                        sum += image.at(x * factor + i, y * factor + j, c);
                    }
                }
                // Round half up: floor(sum / f^2 + 1/2).
                out.at(x, y, c) =
                    static_cast<std::uint8_t>((2 * sum + factor * factor) / (2 * factor * factor));
            }
        }
    }
    return out;
}

namespace {

// The final (aggregated, CA-refined) volume of a level over its grid, plane k = j * cols + i.
Volume final_volume(const Image& left, const Image& right, const CandidateGrid& grid,
                    const LevelParams& level, bool use_ca, CaNeighbours neighbours,
                    std::string_view cost) {
    catalogue::require_cost(cost, catalogue::CostUse::pixel_pair, "the naive hierarchical search");
    const catalogue::Cost id = catalogue::cost(cost).id;
    const bool census = id == catalogue::Cost::census;
    const CostImages images{left, right, id, census ? edge_frontend::naive::luma(left) : Image{},
                            census ? edge_frontend::naive::luma(right) : Image{}};
    const int width = left.width;
    const int height = left.height;
    const int planes = grid.cols * grid.rows;
    const auto kernel = gaussian_kernel(level.window, level.sigma);
    const int r = static_cast<int>(kernel.size()) / 2;
    auto displacement = [&](int x, int y, int k) {
        const std::size_t p = static_cast<std::size_t>(y) * width + x;
        return std::pair{grid.base_d[p] + k % grid.cols, grid.base_v[p] + k / grid.cols};
    };

    // Aggregation: direct 2-D weighted sum, zero outside the image, one rounding shift.
    Volume aggregated(width, height, planes);
    for (int k = 0; k < planes; ++k) {
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                std::int64_t sum = 0;
                for (int j = -r; j <= r; ++j) {
                    for (int i = -r; i <= r; ++i) {
                        if (!aggregated.inside(x + i, y + j)) {
                            continue;
                        }
                        const auto [d, v] = displacement(x + i, y + j, k);
                        sum += static_cast<std::int64_t>(kernel[i + r]) * kernel[j + r] *
                               pixel_cost(images, x + i, y + j, d, v);
                    }
                }
                aggregated.at(x, y, k) = (sum + (1 << (fx::kAggShift - 1))) >> fx::kAggShift;
            }
        }
    }

    Volume final_volume = aggregated;
    if (use_ca) {
        // Rule 1: a candidate neighbour that agrees replaces the cell by its rounded 3x3 mean.
        Volume rule1 = aggregated;
        for (int k = 0; k < planes; ++k) {
            const int i = k % grid.cols;
            const int j = k / grid.cols;
            std::vector<int> neighbour_planes;
            if (i > 0) {
                neighbour_planes.push_back(k - 1);
            }
            if (i + 1 < grid.cols) {
                neighbour_planes.push_back(k + 1);
            }
            if (neighbours == CaNeighbours::horizontal_and_vertical) {
                if (j > 0) {
                    neighbour_planes.push_back(k - grid.cols);
                }
                if (j + 1 < grid.rows) {
                    neighbour_planes.push_back(k + grid.cols);
                }
            }
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    const std::int64_t c = aggregated.at(x, y, k);
                    bool fire = false;
                    for (const int n : neighbour_planes) {
                        fire = fire || agree(aggregated.at(x, y, n), c);
                    }
                    if (!fire) {
                        continue;
                    }
                    std::int64_t sum = 0;
                    for (int dy = -1; dy <= 1; ++dy) {
                        for (int dx = -1; dx <= 1; ++dx) {
                            if (aggregated.inside(x + dx, y + dy)) {
                                sum += aggregated.at(x + dx, y + dy, k);
                            }
                        }
                    }
                    rule1.at(x, y, k) = (2 * sum + 9) / 18;  // round(sum / 9)
                }
            }
        }
        // Rule 2: at least 7 of 8 agreeing in-plane neighbours divide the cell by 1.3.
        for (int k = 0; k < planes; ++k) {
            for (int y = 0; y < height; ++y) {
                for (int x = 0; x < width; ++x) {
                    const std::int64_t c = rule1.at(x, y, k);
                    int count = 0;
                    for (int dy = -1; dy <= 1; ++dy) {
                        for (int dx = -1; dx <= 1; ++dx) {
                            if ((dx != 0 || dy != 0) && rule1.inside(x + dx, y + dy) &&
                                agree(rule1.at(x + dx, y + dy, k), c)) {
                                ++count;
                            }
                        }
                    }
                    final_volume.at(x, y, k) =
                        count >= fx::kRule2MinCount ? (20 * c + 13) / 26 : c;  // round(c / 1.3)
                }
            }
        }
    }

    return final_volume;
}

}  // namespace

LevelMap match_level(const Image& left, const Image& right, const CandidateGrid& grid,
                     const LevelParams& level, bool use_ca, CaNeighbours neighbours,
                     std::string_view cost) {
    const Volume final_volume =
        naive::final_volume(left, right, grid, level, use_ca, neighbours, cost);
    const int width = left.width;
    const int height = left.height;
    const int planes = grid.cols * grid.rows;
    const int r = level.window / 2;
    auto displacement = [&](int x, int y, int k) {
        const std::size_t p = static_cast<std::size_t>(y) * width + x;
        return std::pair{grid.base_d[p] + k % grid.cols, grid.base_v[p] + k / grid.cols};
    };
    // WTA: the smallest cost; among equal costs the smallest (|v - pv|, |d - pd|, v, d).
    LevelMap map{width, height, std::vector<std::int16_t>(static_cast<std::size_t>(width) * height),
                 std::vector<std::int16_t>(static_cast<std::size_t>(width) * height),
                 std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height)};
    const int reach = r + (use_ca ? 1 : 0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t p = map.index(x, y);
            const int pd = grid.prefer_d[p];
            const int pv = grid.prefer_v[p];
            std::tuple<std::int64_t, int, int, int, int> best{};
            for (int k = 0; k < planes; ++k) {
                const auto [d, v] = displacement(x, y, k);
                const std::tuple candidate{final_volume.at(x, y, k), std::abs(v - pv),
                                           std::abs(d - pd), v, d};
                if (k == 0 || candidate < best) {
                    best = candidate;
                }
            }
            const int d = std::get<4>(best);
            const int v = std::get<3>(best);
            map.disparity[p] = static_cast<std::int16_t>(d);
            map.vertical[p] = static_cast<std::int16_t>(v);
            const bool inside = x >= reach && x < width - reach && y >= reach && y < height - reach;
            const bool right_inside = x - d >= reach && y + v >= reach && y + v < height - reach;
            map.valid[p] = inside && right_inside ? 1 : 0;
        }
    }
    return map;
}

std::vector<std::int8_t> vertical_field(const LevelMap& level, int radius,
                                        const std::vector<std::int8_t>& prior, int prior_factor) {
    std::vector<std::int8_t> field(level.valid.size(), 0);
    for (int y = 0; y < level.height; ++y) {
        for (int x = 0; x < level.width; ++x) {
            // Count every vote of the window, directly: each valid winner of the window's rows
            // whose right pixel (i - d, j) lies in the window.
            std::map<int, int> counts;
            for (int j = std::max(0, y - radius); j <= std::min(level.height - 1, y + radius);
                 ++j) {
                for (int i = 0; i < level.width; ++i) {
                    const std::size_t q = static_cast<std::size_t>(j) * level.width + i;
                    const int xr = i - level.disparity[q];
                    if (level.valid[q] != 0 && xr >= 0 && xr >= x - radius && xr <= x + radius) {
                        ++counts[level.vertical[q]];
                    }
                }
            }
            // The largest count; ties to the smaller |v|, then the smaller v.
            std::tuple<int, int, int> best{0, 0, 0};  // (-count, |v|, v)
            for (const auto& [v, n] : counts) {
                best = std::min(best, std::tuple{-n, std::abs(v), v});
            }
            const std::size_t p = static_cast<std::size_t>(y) * level.width + x;
            const int best_count = -std::get<0>(best);
            if (!prior.empty()) {
                const auto found = counts.find(prior[p]);
                const int prior_count = found == counts.end() ? 0 : found->second;
                if (best_count <= prior_factor * prior_count) {
                    field[p] = prior[p];
                    continue;
                }
            }
            field[p] = static_cast<std::int8_t>(std::get<2>(best));
        }
    }
    return field;
}

std::vector<std::int8_t> plane_field(const Plane& plane, int width, int height, int v_min,
                                     int v_max) {
    std::vector<std::int8_t> field(static_cast<std::size_t>(width) * height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            // round half up of the exact rational (a + b x + c y) / 2^16, by long division
            const std::int64_t numerator = plane.a + plane.b * x + plane.c * y;
            std::int64_t v = numerator / kPlaneOne;
            std::int64_t remainder = numerator - v * kPlaneOne;
            if (remainder < 0) {
                --v;
                remainder += kPlaneOne;
            }
            if (2 * remainder >= kPlaneOne) {
                ++v;
            }
            v = v < v_min ? v_min : v > v_max ? v_max : v;
            field[static_cast<std::size_t>(y) * width + x] = static_cast<std::int8_t>(v);
        }
    }
    return field;
}

ValidatedDisparity match_along_field(const Image& left, const Image& right,
                                     const std::vector<std::int8_t>& field, const Params& params) {
    const int width = left.width;
    const int height = left.height;
    // The warped right image, pixel by pixel: row y + v, or the nearest row of the image.
    Image warped(width, height, right.channels);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            int row = y + field[static_cast<std::size_t>(y) * width + x];
            if (row < 0) {
                row = 0;
            }
            if (row > height - 1) {
                row = height - 1;
            }
            for (int c = 0; c < right.channels; ++c) {
                warped.at(x, y, c) = right.at(x, row, c);
            }
        }
    }
    MatchParams pass;
    pass.ndisp = params.ndisp;
    pass.window = params.field_level.window;
    pass.sigma = params.field_level.sigma;
    pass.use_ca = params.use_ca;
    pass.cost = params.cost;
    pass.validation = params.validation;
    ValidatedDisparity out = stereo::naive::match_validated(left, warped, pass);
    const int reach = params.field_level.window / 2 + (params.use_ca ? 1 : 0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t p = static_cast<std::size_t>(y) * width + x;
            if (out.reason[p] != fx::kReasonValid) {
                continue;
            }
            // The match's column: the nearest integer to the sub-pixel disparity, halves up.
            const int d = static_cast<int>(std::floor(out.fixed[p] / 16.0 + 0.5));
            const int xr = std::min(std::max(x - d, 0), width - 1);
            const int row = y + field[static_cast<std::size_t>(y) * width + xr];
            if (row < reach || row >= height - reach) {
                out.reason[p] = fx::kReasonBorder;
                out.fixed[p] = 0;
            }
        }
    }
    return out;
}

Result match(const Image& left, const Image& right, const Params& params) {
    check_pair(left, right);
    hierarchical::validate(params, left.width, left.height);
    const int ndisp = params.ndisp;
    const int vrange = params.vrange == 0 ? params.ndisp : params.vrange;
    Result result;
    const LevelMap* coarse = nullptr;
    for (int level = 0; level < kLevels; ++level) {
        const int f = level == 0 ? 4 : level == 1 ? 2 : 1;
        const Image l = f == 1 ? left : downscale_area(left, f);
        const Image rt = f == 1 ? right : downscale_area(right, f);
        // The level's range: D/f labels from 0, V/f labels centred on 0.
        const int d_max = ndisp / f - 1;
        const int v_min = -((vrange / f) / 2);
        const int v_max = v_min + vrange / f - 1;
        const std::size_t size = static_cast<std::size_t>(l.width) * l.height;
        CandidateGrid grid{l.width, l.height, 0, 0, {}, {}, {}, {}};
        grid.base_d.resize(size);
        grid.base_v.resize(size);
        grid.prefer_d.resize(size);
        grid.prefer_v.resize(size);
        for (int y = 0; y < l.height; ++y) {
            for (int x = 0; x < l.width; ++x) {
                const std::size_t p = static_cast<std::size_t>(y) * l.width + x;
                if (coarse == nullptr) {  // the whole range, ties towards (0, 0)
                    grid.cols = d_max + 1;
                    grid.rows = v_max - v_min + 1;
                    grid.base_d[p] = 0;
                    grid.base_v[p] = static_cast<std::int16_t>(v_min);
                    grid.prefer_d[p] = 0;
                    grid.prefer_v[p] = 0;
                    continue;
                }
                // 3x3 around twice the parent's winner, the centre moved inside the range.
                const int px = std::min(x / 2, coarse->width - 1);
                const int py = std::min(y / 2, coarse->height - 1);
                const std::size_t parent = static_cast<std::size_t>(py) * coarse->width + px;
                int cd = 2 * coarse->disparity[parent];
                int cv = 2 * coarse->vertical[parent];
                cd = cd < 1 ? 1 : cd > d_max - 1 ? d_max - 1 : cd;
                cv = cv < v_min + 1 ? v_min + 1 : cv > v_max - 1 ? v_max - 1 : cv;
                grid.cols = 3;
                grid.rows = 3;
                grid.base_d[p] = static_cast<std::int16_t>(cd - 1);
                grid.base_v[p] = static_cast<std::int16_t>(cv - 1);
                grid.prefer_d[p] = static_cast<std::int16_t>(cd);
                grid.prefer_v[p] = static_cast<std::int16_t>(cv);
            }
        }
        const auto l_index = static_cast<std::size_t>(level);
        result.levels[l_index] = match_level(l, rt, grid, params.levels[l_index], params.use_ca,
                                             params.neighbours, params.cost);
        result.cost_evaluations.level[l_index] =
            static_cast<std::int64_t>(size) * grid.cols * grid.rows;
        coarse = &result.levels[l_index];
    }
    if (params.output == Output::full_level) {
        return finish(std::move(result.levels), result.cost_evaluations);
    }
    // The field (the plane fit is the model's, checked by its own test), then the 1-D pass.
    const LevelMap& full = result.levels[kLevels - 1];
    std::vector<std::int8_t> field;
    if (params.field_model == FieldModel::mode) {
        field = naive::vertical_field(full, params.field_radius, {}, 0);
    } else if (params.field_model == FieldModel::radial ||
               params.field_model == FieldModel::mode_with_radial_prior) {
        // The radial fit and its field are the model's (checked by their own tests).
        const int v_min = -(vrange / 2);
        const Plane plane = hierarchical::vertical_plane(full);
        const std::optional<RadialModel> lens =
            hierarchical::vertical_radial(full, plane, params.radial_min_gain);
        field = lens
                    ? hierarchical::radial_field(*lens, full, v_min, v_min + vrange - 1)
                    : naive::plane_field(plane, full.width, full.height, v_min, v_min + vrange - 1);
        if (params.field_model == FieldModel::mode_with_radial_prior) {
            field = naive::vertical_field(full, params.field_radius, field, params.prior_factor);
        }
    } else {
        const int v_min = -(vrange / 2);
        field = naive::plane_field(hierarchical::vertical_plane(full), full.width, full.height,
                                   v_min, v_min + vrange - 1);
        if (params.field_model == FieldModel::mode_with_plane_prior) {
            field = naive::vertical_field(full, params.field_radius, field, params.prior_factor);
        }
    }
    ValidatedDisparity validated = naive::match_along_field(left, right, field, params);
    result.cost_evaluations.field_pass =
        static_cast<std::int64_t>(left.width) * left.height * params.ndisp;
    return finish_field(std::move(result.levels), result.cost_evaluations, std::move(field),
                        std::move(validated));
}

}  // namespace stereo::hierarchical::naive
