#include "stereo_robot/slam/maps.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <unordered_set>

#include <opencv2/imgproc.hpp>

namespace stereo::robot::slam {

// ---- v-disparity --------------------------------------------------------------------------

VDisparity v_disparity(const SparseDisparity& map, int ndisp) {
    VDisparity out{map.height, ndisp,
                   std::vector<int>(static_cast<std::size_t>(map.height) * ndisp)};
    for (int v = 0; v < map.height; ++v) {
        for (int u = 0; u < map.width; ++u) {
            const float d = map.at(u, v);
            if (d < 0.0f) {
                continue;
            }
            const int label = static_cast<int>(std::lround(d));
            if (label < ndisp) {
                ++out.counts[static_cast<std::size_t>(v) * ndisp + label];
            }
        }
    }
    return out;
}

namespace {

struct Peak {
    double v;
    double d;
    double votes;
};

double support(const std::vector<Peak>& peaks, const GroundLine& line, double tolerance,
               int* rows = nullptr) {
    double total = 0.0;
    int count = 0;
    for (const Peak& p : peaks) {
        if (std::abs(p.d - line.disparity(p.v)) <= tolerance) {
            total += p.votes;
            ++count;
        }
    }
    if (rows != nullptr) {
        *rows = count;
    }
    return total;
}

std::optional<GroundLine> weighted_fit(const std::vector<Peak>& peaks, const GroundLine& line,
                                       double tolerance) {
    double sw = 0, sv = 0, sd = 0, svv = 0, svd = 0;
    for (const Peak& p : peaks) {
        if (std::abs(p.d - line.disparity(p.v)) <= tolerance) {
            sw += p.votes;
            sv += p.votes * p.v;
            sd += p.votes * p.d;
            svv += p.votes * p.v * p.v;
            svd += p.votes * p.v * p.d;
        }
    }
    const double det = sw * svv - sv * sv;
    if (!(det > 0.0)) {
        return std::nullopt;
    }
    const double slope = (sw * svd - sv * sd) / det;
    return GroundLine{slope, (sd - slope * sv) / sw};
}

}  // namespace

std::optional<GroundLine> fit_ground_line(const VDisparity& vdisp, const Camera& camera,
                                          const GroundParams& params) {
    const double min_slope = camera.baseline / params.max_height;
    const double max_slope = camera.baseline / params.min_height;
    const double max_horizon_offset =
        camera.focal * std::tan(params.max_pitch_deg * std::numbers::pi / 180.0);
    const auto plausible = [&](const GroundLine& line) {
        return line.slope >= min_slope && line.slope <= max_slope &&
               std::abs(-line.intercept / line.slope - camera.cy) <= max_horizon_offset;
    };
    std::vector<Peak> peaks;
    for (int v = 0; v < vdisp.rows; ++v) {
        int best = 1;
        for (int d = 2; d < vdisp.ndisp; ++d) {
            if (vdisp.at(v, d) > vdisp.at(v, best)) {
                best = d;
            }
        }
        if (vdisp.ndisp > 1 && vdisp.at(v, best) >= params.min_votes) {
            peaks.push_back({static_cast<double>(v), static_cast<double>(best),
                             static_cast<double>(vdisp.at(v, best))});
        }
    }
    if (static_cast<int>(peaks.size()) < std::max(2, params.min_rows)) {
        return std::nullopt;
    }
    std::mt19937 rng(params.seed);
    std::uniform_int_distribution<std::size_t> pick(0, peaks.size() - 1);
    std::optional<GroundLine> best;
    double best_support = 0.0;
    for (int iteration = 0; iteration < params.iterations; ++iteration) {
        const Peak& a = peaks[pick(rng)];
        const Peak& b = peaks[pick(rng)];
        if (a.v == b.v) {
            continue;
        }
        const double slope = (b.d - a.d) / (b.v - a.v);
        const GroundLine line{slope, a.d - slope * a.v};
        if (!plausible(line)) {
            continue;
        }
        const double s = support(peaks, line, params.tolerance);
        if (s > best_support) {
            best_support = s;
            best = line;
        }
    }
    if (!best) {
        return std::nullopt;
    }
    const auto refined = weighted_fit(peaks, *best, params.tolerance);
    if (!refined || !plausible(*refined)) {
        return std::nullopt;
    }
    int rows = 0;
    support(peaks, *refined, params.tolerance, &rows);
    if (rows < params.min_rows) {
        return std::nullopt;
    }
    return refined;
}

cv::Mat draw_v_disparity(const VDisparity& vdisp, const std::optional<GroundLine>& line,
                         double tolerance, int scale) {
    const int most =
        vdisp.counts.empty() ? 0 : *std::max_element(vdisp.counts.begin(), vdisp.counts.end());
    cv::Mat grey(vdisp.rows, vdisp.ndisp, CV_8UC1, cv::Scalar(0));
    for (int v = 0; v < vdisp.rows; ++v) {
        for (int d = 0; d < vdisp.ndisp; ++d) {
            const double level = most > 0 ? std::log1p(vdisp.at(v, d)) / std::log1p(most) : 0.0;
            grey.at<std::uint8_t>(v, d) = static_cast<std::uint8_t>(std::lround(255.0 * level));
        }
    }
    cv::Mat big;
    cv::resize(grey, big, cv::Size(vdisp.ndisp * scale, vdisp.rows * scale), 0, 0,
               cv::INTER_NEAREST);
    cv::Mat picture;
    cv::cvtColor(big, picture, cv::COLOR_GRAY2BGR);
    if (line) {
        // Points in picture coordinates: column (d + 0.5) * scale, row (v + 0.5) * scale.
        const auto point = [&](double v, double offset) {
            return cv::Point2d((line->disparity(v) + offset + 0.5) * scale, (v + 0.5) * scale);
        };
        const double top = 0.0;
        const double bottom = vdisp.rows - 1.0;
        cv::line(picture, point(top, 0), point(bottom, 0), cv::Scalar(0, 0, 255), 1, cv::LINE_AA);
        for (const double side : {-tolerance, tolerance}) {
            cv::line(picture, point(top, side), point(bottom, side), cv::Scalar(0, 200, 255), 1,
                     cv::LINE_AA);
        }
    }
    return picture;
}

// ---- local map ----------------------------------------------------------------------------

LocalMap local_map(const SparseDisparity& map, const GroundLine& line, const Camera& camera,
                   const LocalMapParams& params) {
    LocalMap out;
    const int stride = std::max(1, params.stride);
    for (int v = 0; v < map.height; v += stride) {
        const double ground = line.disparity(v);
        for (int u = 0; u < map.width; u += stride) {
            const double d = map.at(u, v);
            if (!(d > 0.0)) {
                continue;
            }
            const Eigen::Vector3d point = camera.lift(u, v, d);
            if (point.z() > params.max_range) {
                continue;
            }
            if (std::abs(d - ground) <= params.tolerance) {
                out.ground.push_back(point);
            } else if (d > ground + params.tolerance) {
                // The ground at this depth is seen at row (d - b) / a; the rows between, times
                // Z / f = B / d metres per row, are the height above it.
                const double ground_row = (d - line.intercept) / line.slope;
                const double height =
                    camera.baseline * (ground_row - v) / (d + camera.disparity_offset);
                if (height <= params.max_height) {
                    out.obstacles.push_back(point);
                }
            }
        }
    }
    return out;
}

// ---- grids --------------------------------------------------------------------------------

CellIndex cell_of(const Eigen::Vector2d& point, double cell_size) {
    return {static_cast<int>(std::floor(point.x() / cell_size)),
            static_cast<int>(std::floor(point.y() / cell_size))};
}

std::size_t DenseGrid::count(Cell state) const {
    return static_cast<std::size_t>(std::count(cells.begin(), cells.end(), state));
}

std::vector<Ray> bearing_rays(const Eigen::Vector2d& origin,
                              const std::vector<Eigen::Vector2d>& obstacles,
                              const std::vector<Eigen::Vector2d>& ground, double cell_size,
                              double bin_deg) {
    struct Bin {
        double nearest_obstacle = std::numeric_limits<double>::infinity();
        Eigen::Vector2d obstacle;
        double farthest_ground = -1.0;
        Eigen::Vector2d free;
    };
    std::map<int, Bin> bins;
    const auto bin_of = [&](const Eigen::Vector2d& p) {
        const Eigen::Vector2d r = p - origin;
        const double bearing = std::atan2(r.x(), r.y()) * 180.0 / std::numbers::pi;
        return static_cast<int>(std::floor(bearing / bin_deg));
    };
    for (const auto& p : obstacles) {
        Bin& bin = bins[bin_of(p)];
        const double range = (p - origin).norm();
        if (range < bin.nearest_obstacle) {
            bin.nearest_obstacle = range;
            bin.obstacle = p;
        }
    }
    for (const auto& p : ground) {
        Bin& bin = bins[bin_of(p)];
        const double range = (p - origin).norm();
        if (range > bin.farthest_ground) {
            bin.farthest_ground = range;
            bin.free = p;
        }
    }
    std::vector<Ray> rays;
    for (const auto& [index, bin] : bins) {
        if (std::isfinite(bin.nearest_obstacle)) {
            rays.push_back({cell_of(bin.obstacle, cell_size), false});
        } else {
            rays.push_back({cell_of(bin.free, cell_size), true});
        }
    }
    return rays;
}

EvidenceGrid::EvidenceGrid(double cell_size) : cell_size_(cell_size) {
    if (!(cell_size > 0.0) || !std::isfinite(cell_size)) {
        throw std::invalid_argument("cell size must be a positive number of metres");
    }
}

std::int64_t EvidenceGrid::key(const CellIndex& cell) {
    return (static_cast<std::int64_t>(cell.x) << 32) ^
           static_cast<std::int64_t>(static_cast<std::uint32_t>(cell.z));
}

std::vector<CellIndex> line_cells(const CellIndex& a, const CellIndex& b) {
    std::vector<CellIndex> cells;
    const int dx = std::abs(b.x - a.x);
    const int dz = -std::abs(b.z - a.z);
    const int sx = a.x < b.x ? 1 : -1;
    const int sz = a.z < b.z ? 1 : -1;
    int error = dx + dz;
    CellIndex c = a;
    while (true) {
        cells.push_back(c);
        if (c == b) {
            break;
        }
        const int twice = 2 * error;
        if (twice >= dz) {
            error += dz;
            c.x += sx;
        }
        if (twice <= dx) {
            error += dx;
            c.z += sz;
        }
    }
    return cells;
}

void EvidenceGrid::add_frame(const CellIndex& origin, const std::vector<CellIndex>& obstacles,
                             const std::vector<Ray>& rays) {
    std::unordered_set<std::int64_t> hit;
    std::unordered_set<std::int64_t> missed;
    for (const CellIndex& cell : obstacles) {
        hit.insert(key(cell));
    }
    for (const Ray& ray : rays) {
        std::vector<CellIndex> cells = line_cells(origin, ray.end);
        if (!ray.end_is_free) {
            cells.pop_back();
        }
        for (const CellIndex& cell : cells) {
            missed.insert(key(cell));
        }
    }
    for (const std::int64_t k : hit) {
        ++cells_[k].hits;
    }
    for (const std::int64_t k : missed) {
        ++cells_[k].misses;
    }
}

Cell EvidenceGrid::state(const CellIndex& cell) const {
    const auto found = cells_.find(key(cell));
    if (found == cells_.end()) {
        return Cell::unknown;
    }
    const Evidence& e = found->second;
    if (e.hits >= 1 && e.hits >= e.misses) {
        return Cell::occupied;
    }
    return e.misses > 0 ? Cell::free : Cell::unknown;
}

DenseGrid EvidenceGrid::to_dense(const std::vector<CellIndex>& extra, int margin) const {
    if (cells_.empty() && extra.empty()) {
        return DenseGrid(0, 0, 1, 1);
    }
    int x_min = std::numeric_limits<int>::max();
    int z_min = std::numeric_limits<int>::max();
    int x_max = std::numeric_limits<int>::min();
    int z_max = std::numeric_limits<int>::min();
    const auto include = [&](const CellIndex& c) {
        x_min = std::min(x_min, c.x);
        z_min = std::min(z_min, c.z);
        x_max = std::max(x_max, c.x);
        z_max = std::max(z_max, c.z);
    };
    for (const auto& [k, evidence] : cells_) {
        include({static_cast<int>(k >> 32), static_cast<int>(static_cast<std::uint32_t>(k))});
    }
    for (const CellIndex& c : extra) {
        include(c);
    }
    DenseGrid grid(x_min - margin, z_min - margin, x_max - x_min + 1 + 2 * margin,
                   z_max - z_min + 1 + 2 * margin);
    for (int row = 0; row < grid.height; ++row) {
        for (int column = 0; column < grid.width; ++column) {
            grid.at(column, row) = state({grid.x0 + column, grid.z0 + row});
        }
    }
    return grid;
}

DenseGrid ca_clean(const DenseGrid& grid) {
    DenseGrid out = grid;
    const auto at = [&](int c, int r) {
        if (c < 0 || r < 0 || c >= grid.width || r >= grid.height) {
            return Cell::unknown;
        }
        return grid.at(c, r);
    };
    const auto occupied = [&](int c, int r) { return at(c, r) == Cell::occupied; };
    for (int r = 0; r < grid.height; ++r) {
        for (int c = 0; c < grid.width; ++c) {
            int occupied_neighbours = 0;
            int free_neighbours = 0;
            for (int dr = -1; dr <= 1; ++dr) {
                for (int dc = -1; dc <= 1; ++dc) {
                    if (dr != 0 || dc != 0) {
                        occupied_neighbours += occupied(c + dc, r + dr) ? 1 : 0;
                        free_neighbours += at(c + dc, r + dr) == Cell::free ? 1 : 0;
                    }
                }
            }
            if (grid.at(c, r) == Cell::occupied) {
                if (occupied_neighbours == 0) {
                    out.at(c, r) = free_neighbours > 0 ? Cell::free : Cell::unknown;
                }
            } else if ((occupied(c - 1, r) && occupied(c + 1, r)) ||
                       (occupied(c, r - 1) && occupied(c, r + 1)) ||
                       (occupied(c - 1, r - 1) && occupied(c + 1, r + 1)) ||
                       (occupied(c + 1, r - 1) && occupied(c - 1, r + 1))) {
                out.at(c, r) = Cell::occupied;
            }
        }
    }
    return out;
}

// ---- map merging --------------------------------------------------------------------------

namespace {

Eigen::Vector2d rotate_about(const Eigen::Vector2d& p, const Eigen::Vector2d& pivot, double angle) {
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    const Eigen::Vector2d r = p - pivot;
    return pivot + Eigen::Vector2d(c * r.x() + s * r.y(), -s * r.x() + c * r.y());
}

double radians(double degrees) {
    return degrees * std::numbers::pi / 180.0;
}

// The distinct cells in (x, z) order, as sort + unique would leave them. A local map's cells lie
// in a box of a few hundred cells a side, so marking them in a bitmap of that box and reading it
// row by row is linear; sorting tens of thousands of points per rotation took a tenth of a SLAM
// step. Boxes too large for the bitmap (scattered outliers) are sorted.
void sort_unique_cells(std::vector<CellIndex>& cells) {
    if (cells.empty()) {
        return;
    }
    const auto [min_x, max_x] =
        std::minmax_element(cells.begin(), cells.end(),
                            [](const CellIndex& a, const CellIndex& b) { return a.x < b.x; });
    const auto [min_z, max_z] =
        std::minmax_element(cells.begin(), cells.end(),
                            [](const CellIndex& a, const CellIndex& b) { return a.z < b.z; });
    const std::int64_t width = static_cast<std::int64_t>(max_x->x) - min_x->x + 1;
    const std::int64_t depth = static_cast<std::int64_t>(max_z->z) - min_z->z + 1;
    constexpr std::int64_t kMaxBitmap = std::int64_t{1} << 24;
    if (width * depth > kMaxBitmap) {
        std::sort(cells.begin(), cells.end(), [](const CellIndex& a, const CellIndex& b) {
            return a.x != b.x ? a.x < b.x : a.z < b.z;
        });
        cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
        return;
    }
    const int x0 = min_x->x;
    const int z0 = min_z->z;
    std::vector<std::uint8_t> seen(static_cast<std::size_t>(width * depth), 0);
    for (const CellIndex& c : cells) {
        seen[static_cast<std::size_t>((c.x - x0) * depth + (c.z - z0))] = 1;
    }
    cells.clear();
    for (std::int64_t i = 0; i < width * depth; ++i) {
        if (seen[static_cast<std::size_t>(i)] != 0) {
            cells.push_back({x0 + static_cast<int>(i / depth), z0 + static_cast<int>(i % depth)});
        }
    }
}

}  // namespace

MergeResult best_placement(const EvidenceGrid& global, const std::vector<Eigen::Vector2d>& points,
                           const Eigen::Vector2d& pivot, const MergeParams& params) {
    // The distinct cells of the points under each rotation.
    std::vector<std::vector<CellIndex>> rotated;
    for (int step = -params.angle_steps; step <= params.angle_steps; ++step) {
        const double angle = radians(step * params.angle_step_deg);
        std::vector<CellIndex> cells;
        cells.reserve(points.size());
        for (const auto& p : points) {
            cells.push_back(cell_of(rotate_about(p, pivot, angle), global.cell_size()));
        }
        sort_unique_cells(cells);
        rotated.push_back(std::move(cells));
    }
    // The map's occupancy over the box the shifted cells can reach, read once: the search looks
    // every cell up once per shift, and the map is a hash table.
    CellIndex low{std::numeric_limits<int>::max(), std::numeric_limits<int>::max()};
    CellIndex high{std::numeric_limits<int>::min(), std::numeric_limits<int>::min()};
    for (const auto& cells : rotated) {
        for (const CellIndex& c : cells) {
            low = {std::min(low.x, c.x), std::min(low.z, c.z)};
            high = {std::max(high.x, c.x), std::max(high.z, c.z)};
        }
    }
    const std::int64_t shift = params.max_shift;
    const std::int64_t width = static_cast<std::int64_t>(high.x) - low.x + 1 + 2 * shift;
    const std::int64_t depth = static_cast<std::int64_t>(high.z) - low.z + 1 + 2 * shift;
    constexpr std::int64_t kMaxWindow = std::int64_t{1} << 22;
    std::vector<std::uint8_t> window;
    if (low.x <= high.x && width * depth <= kMaxWindow) {
        window.resize(static_cast<std::size_t>(width * depth));
        for (std::int64_t i = 0; i < width; ++i) {
            for (std::int64_t j = 0; j < depth; ++j) {
                const CellIndex cell{static_cast<int>(low.x - shift + i),
                                     static_cast<int>(low.z - shift + j)};
                window[static_cast<std::size_t>(i * depth + j)] = global.occupied(cell) ? 1 : 0;
            }
        }
    }
    const auto occupied = [&](int x, int z) {
        if (window.empty()) {
            return global.occupied({x, z});
        }
        const std::int64_t i = static_cast<std::int64_t>(x) - (low.x - shift);
        const std::int64_t j = static_cast<std::int64_t>(z) - (low.z - shift);
        return window[static_cast<std::size_t>(i * depth + j)] != 0;
    };

    MergeResult best;
    bool first = true;
    int best_size = 0;
    for (int step = -params.angle_steps; step <= params.angle_steps; ++step) {
        const std::vector<CellIndex>& cells =
            rotated[static_cast<std::size_t>(step + params.angle_steps)];
        for (int dz = -params.max_shift; dz <= params.max_shift; ++dz) {
            for (int dx = -params.max_shift; dx <= params.max_shift; ++dx) {
                int score = 0;
                for (const CellIndex& c : cells) {
                    score += occupied(c.x + dx, c.z + dz) ? 1 : 0;
                }
                const int size = std::abs(dx) + std::abs(dz) + std::abs(step);
                if (step == 0 && dx == 0 && dz == 0) {
                    best.base_score = score;
                }
                if (first || score > best.score || (score == best.score && size < best_size)) {
                    best.dx = dx;
                    best.dz = dz;
                    best.dtheta = step;
                    best.score = score;
                    best.cells = static_cast<int>(cells.size());
                    best_size = size;
                    first = false;
                }
            }
        }
    }
    // The gates (docs/slam.md): a gain noise cannot explain (sigma * sqrt of the counts, the
    // Poisson spread of a count of chance coincidences), and a local map that the global map
    // confirms (at least min_match of its cells on occupied cells once placed).
    const int gain = best.score - best.base_score;
    const bool significant =
        gain >= params.min_gain &&
        gain >= params.significance * std::sqrt(static_cast<double>(best.score + best.base_score));
    const bool confirmed =
        best.cells > 0 && best.score >= params.min_match * static_cast<double>(best.cells);
    const auto on_edge = [](int value, int range) { return range > 0 && std::abs(value) == range; };
    best.at_edge = on_edge(best.dx, params.max_shift) || on_edge(best.dz, params.max_shift) ||
                   on_edge(best.dtheta, params.angle_steps);
    best.applied =
        significant && confirmed && best_size > 0 && !(params.reject_edge && best.at_edge);
    return best;
}

Eigen::Isometry3d merge_correction(const MergeResult& result, const Eigen::Vector2d& pivot,
                                   double cell_size, const MergeParams& params) {
    Eigen::Isometry3d correction = Eigen::Isometry3d::Identity();
    if (!result.applied) {
        return correction;
    }
    const double angle = radians(result.dtheta * params.angle_step_deg);
    const Eigen::Vector3d centre(pivot.x(), 0.0, pivot.y());
    const Eigen::Matrix3d rotation = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).matrix();
    correction.linear() = rotation;
    correction.translation() = centre - rotation * centre +
                               Eigen::Vector3d(result.dx * cell_size, 0.0, result.dz * cell_size);
    return correction;
}

// ---- pictures -----------------------------------------------------------------------------

cv::Mat render_map(const DenseGrid& grid, double cell_size, const std::vector<Polyline>& paths,
                   int pixels) {
    cv::Mat picture(grid.height * pixels, grid.width * pixels, CV_8UC3);
    for (int row = 0; row < grid.height; ++row) {
        for (int column = 0; column < grid.width; ++column) {
            const Cell state = grid.at(column, row);
            const cv::Scalar colour = state == Cell::occupied ? cv::Scalar(0, 0, 0)
                                      : state == Cell::free   ? cv::Scalar(255, 255, 255)
                                                              : cv::Scalar(150, 150, 150);
            const int top = (grid.height - 1 - row) * pixels;
            picture(cv::Rect(column * pixels, top, pixels, pixels)).setTo(colour);
        }
    }
    const auto to_pixel = [&](const Eigen::Vector2d& p) {
        return cv::Point2d((p.x() / cell_size - grid.x0) * pixels,
                           (grid.z0 + grid.height - p.y() / cell_size) * pixels);
    };
    for (const Polyline& path : paths) {
        for (std::size_t i = 1; i < path.points.size(); ++i) {
            cv::line(picture, to_pixel(path.points[i - 1]), to_pixel(path.points[i]), path.colour,
                     2, cv::LINE_AA);
        }
        if (!path.points.empty()) {
            cv::circle(picture, to_pixel(path.points.front()), 4, path.colour, cv::FILLED);
        }
    }
    // A strip below the map: legend, scale bar and axes (the map's pixels stay where they are).
    constexpr int kStrip = 70;
    const int width = std::max(picture.cols, 560);
    cv::Mat out(picture.rows + kStrip, width, CV_8UC3, cv::Scalar(255, 255, 255));
    picture.copyTo(out(cv::Rect(0, 0, picture.cols, picture.rows)));
    const cv::Scalar ink(0, 0, 0);
    const int y0 = picture.rows + 18;
    int x = 8;
    const auto swatch = [&](const cv::Scalar& colour, const std::string& text, bool line) {
        if (line) {
            cv::line(out, {x, y0}, {x + 18, y0}, colour, 2, cv::LINE_AA);
        } else {
            cv::rectangle(out, cv::Rect(x, y0 - 6, 12, 12), colour, cv::FILLED);
            cv::rectangle(out, cv::Rect(x, y0 - 6, 12, 12), ink, 1);
        }
        cv::putText(out, text, {x + 24, y0 + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.45, ink, 1,
                    cv::LINE_AA);
        x += 24 + 9 * static_cast<int>(text.size()) + 14;
    };
    swatch(cv::Scalar(0, 0, 0), "occupied", false);
    swatch(cv::Scalar(255, 255, 255), "free", false);
    swatch(cv::Scalar(150, 150, 150), "unknown", false);
    for (const Polyline& path : paths) {
        if (!path.label.empty()) {
            swatch(path.colour, path.label, true);
        }
    }
    // Scale bar: the largest of 1, 2, 5, 10, 20, 50, 100 m that fits a quarter of the width.
    double metres = 1.0;
    for (const double m : {2.0, 5.0, 10.0, 20.0, 50.0, 100.0}) {
        if (m / cell_size * pixels <= width / 4.0) {
            metres = m;
        }
    }
    const int bar = static_cast<int>(std::lround(metres / cell_size * pixels));
    const int y1 = picture.rows + 48;
    cv::line(out, {8, y1}, {8 + bar, y1}, ink, 2);
    for (const int end : {8, 8 + bar}) {
        cv::line(out, {end, y1 - 5}, {end, y1 + 5}, ink, 2);
    }
    char text[64];
    std::snprintf(text, sizeof text, "%g m (cell %g m)", metres, cell_size);
    cv::putText(out, text, {16 + bar, y1 + 5}, cv::FONT_HERSHEY_SIMPLEX, 0.45, ink, 1, cv::LINE_AA);
    // Axes: x to the right, z (forward at the first frame) up.
    const cv::Point origin(width - 60, picture.rows + 60);
    cv::arrowedLine(out, origin, origin + cv::Point(40, 0), ink, 1, cv::LINE_AA, 0, 0.25);
    cv::arrowedLine(out, origin, origin + cv::Point(0, -40), ink, 1, cv::LINE_AA, 0, 0.25);
    cv::putText(out, "x", origin + cv::Point(44, 4), cv::FONT_HERSHEY_SIMPLEX, 0.45, ink, 1,
                cv::LINE_AA);
    cv::putText(out, "z", origin + cv::Point(-14, -32), cv::FONT_HERSHEY_SIMPLEX, 0.45, ink, 1,
                cv::LINE_AA);
    return out;
}

}  // namespace stereo::robot::slam
