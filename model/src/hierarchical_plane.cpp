// The plane field's hardware form: statistics per frame, the host's fit between frames
// (stereo/hierarchical_plane.hpp, docs/hierarchical.md "Hardware form of the field").
#include "stereo/hierarchical_plane.hpp"

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <utility>

namespace stereo::hierarchical {

bool is_plane_inlier(int x, int y, int v, const PlaneSetting& setting) {
    const Plane& plane = setting.plane;
    const std::int64_t residual = v * kPlaneOne - (plane.a + plane.b * x + plane.c * y);
    return std::abs(residual) <= setting.tolerance;
}

PlaneStatistics plane_statistics(const LevelMap& level, const PlaneSetting& setting, int v_min,
                                 int v_max) {
    if (v_max < v_min) {
        throw std::invalid_argument("plane_statistics: empty offset range");
    }
    PlaneStatistics s;
    s.v_min = v_min;
    s.histogram.assign(static_cast<std::size_t>(v_max - v_min + 1), 0);
    for (int y = 0; y < level.height; ++y) {
        for (int x = 0; x < level.width; ++x) {
            const std::size_t p = level.index(x, y);
            const int column = right_column(level, x, y);
            if (level.valid[p] == 0 || column < 0 || column >= level.width) {
                continue;  // no vote
            }
            const int v = level.vertical[p];
            if (v < v_min || v > v_max) {
                throw std::invalid_argument("plane_statistics: offset " + std::to_string(v) +
                                            " outside [" + std::to_string(v_min) + ", " +
                                            std::to_string(v_max) + "]");
            }
            ++s.histogram[static_cast<std::size_t>(v - v_min)];
            const int xr = column;
            if (!is_plane_inlier(xr, y, v, setting)) {
                continue;
            }
            ++s.count;
            s.sum_x += xr;
            s.sum_y += y;
            s.sum_xx += std::int64_t{xr} * xr;
            s.sum_xy += std::int64_t{xr} * y;
            s.sum_yy += std::int64_t{y} * y;
            s.sum_v += v;
            s.sum_xv += std::int64_t{xr} * v;
            s.sum_yv += std::int64_t{y} * v;
        }
    }
    return s;
}

int histogram_mode(const PlaneStatistics& statistics) {
    int mode = 0;
    std::int64_t best = 0;
    for (std::size_t i = 0; i < statistics.histogram.size(); ++i) {
        const int v = statistics.v_min + static_cast<int>(i);
        const std::int64_t n = statistics.histogram[i];
        if (n > best || (n == best && n > 0 && std::abs(v) < std::abs(mode))) {
            mode = v;
            best = n;
        }
    }
    return mode;
}

std::optional<Plane> solve_plane(const PlaneStatistics& statistics) {
    const auto d = [](std::int64_t value) { return static_cast<double>(value); };
    // Normal equations of v = a + b x + c y; the sums are exact integers below 2^53.
    const double s[3][3] = {{d(statistics.count), d(statistics.sum_x), d(statistics.sum_y)},
                            {d(statistics.sum_x), d(statistics.sum_xx), d(statistics.sum_xy)},
                            {d(statistics.sum_y), d(statistics.sum_xy), d(statistics.sum_yy)}};
    const double r[3] = {d(statistics.sum_v), d(statistics.sum_xv), d(statistics.sum_yv)};
    const auto determinant = [](const double(&m)[3][3]) {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
               m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    };
    const double det = determinant(s);
    if (statistics.count < 3 || std::abs(det) < 1e-9 * std::abs(s[0][0] * s[1][1] * s[2][2]) ||
        det == 0.0) {
        return std::nullopt;  // too few or collinear inliers
    }
    // Cramer's rule, each coefficient rounded to 1/kPlaneOne.
    const auto coefficient = [&](int column) {
        double m[3][3];
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) {
                m[i][j] = j == column ? r[i] : s[i][j];
            }
        }
        return static_cast<std::int64_t>(
            std::llround(determinant(m) / det * static_cast<double>(kPlaneOne)));
    };
    return Plane{coefficient(0), coefficient(1), coefficient(2)};
}

void PlaneTracker::update(const PlaneStatistics& frame) {
    if (!from_mode_) {
        if (const std::optional<Plane> solved = solve_plane(frame)) {
            setting_ = {*solved, kFitTolerance};
            return;
        }
    }
    setting_ = {Plane{histogram_mode(frame) * kPlaneOne, 0, 0}, kFirstFitTolerance};
    from_mode_ = false;
}

void PlaneTracker::restart() {
    setting_ = {};
    from_mode_ = true;
}

FrameResult match_frame(const Image& left, const Image& right, const Params& params,
                        const PlaneSetting& setting) {
    CostCount count;
    std::array<LevelMap, kLevels> levels = match_levels(left, right, params, count);
    const SearchRange range = level_range(params, 1);
    std::vector<std::int8_t> field =
        plane_field(setting.plane, left.width, left.height, range.v_min, range.v_max);
    ValidatedDisparity validated = match_along_field(left, right, field, params, count.field_pass);
    PlaneStatistics statistics =
        plane_statistics(levels[kLevels - 1], setting, range.v_min, range.v_max);
    return {finish_field(std::move(levels), count, std::move(field), std::move(validated)),
            std::move(statistics)};
}

}  // namespace stereo::hierarchical
