// Local and global maps of the SLAM layer (thesis Sec. 4.2.3-4.2.4): the v-disparity image and
// its ground line, 2-D occupancy grids of the ground plane, the map-merging search and the
// cellular-automaton clean-up. Rules and defaults: docs/slam.md.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "stereo_robot/slam/frontend.hpp"
#include "stereo_robot/slam/motion.hpp"

namespace stereo::robot::slam {

// ---- v-disparity --------------------------------------------------------------------------
// counts(v, d): validated pixels of row v whose disparity rounds to d (0 <= d < ndisp).
struct VDisparity {
    int rows = 0;
    int ndisp = 0;
    std::vector<int> counts;
    int at(int v, int d) const { return counts[static_cast<std::size_t>(v) * ndisp + d]; }
};

VDisparity v_disparity(const SparseDisparity& map, int ndisp);

// The ground in the v-disparity image: d = slope * v + intercept.
struct GroundLine {
    double slope = 0.0;
    double intercept = 0.0;
    double disparity(double v) const { return slope * v + intercept; }
};

struct GroundParams {
    int min_votes = 5;        // a row's peak must hold this many pixels to be a candidate
    double tolerance = 1.0;   // pixels of disparity either side of the line (the ground band)
    double min_height = 0.1;  // camera height above the ground, metres: slope = B / height
    double max_height = 3.0;
    double max_pitch_deg = 15.0;  // the line's zero (the horizon) lies within f tan(this) of cy
    int min_rows = 10;            // rows on the line needed to accept it
    int iterations = 300;
    std::uint32_t seed = 1;
};

// Robust line fit: the peak (largest count, d >= 1) of every row with at least min_votes
// pixels is a candidate; RANSAC over pairs of candidates keeps lines that a flat ground could
// make with this camera (slope B / h for h in [min_height, max_height], horizon row -b / a
// within f tan(max_pitch) of cy) and maximises the summed peak counts within `tolerance`; then
// a count-weighted least-squares fit on those inliers, which must pass the same checks. Nothing
// when fewer than min_rows rows support the best line.
std::optional<GroundLine> fit_ground_line(const VDisparity& vdisp, const Camera& camera,
                                          const GroundParams& params);

// The v-disparity image (log-scaled counts, white = many) with the line and its band drawn.
cv::Mat draw_v_disparity(const VDisparity& vdisp, const std::optional<GroundLine>& line,
                         double tolerance, int scale = 2);

// ---- local map ----------------------------------------------------------------------------
struct LocalMapParams {
    double max_range = 20.0;  // metres along z: farther points are left out
    double max_height = 2.0;  // metres above the ground: higher points do not block a robot
    double tolerance = 1.0;   // the ground band, pixels of disparity (as GroundParams)
    int stride = 1;           // use every stride-th pixel in x and y
};

// Camera-frame 3-D points of one frame, split by the ground line.
struct LocalMap {
    std::vector<Eigen::Vector3d> obstacles;  // above the ground band and below max_height
    std::vector<Eigen::Vector3d> ground;     // inside the band: free space the camera sees
};

// A validated pixel (u, v, d) is ground when |d - line(v)| <= tolerance, an obstacle when
// d > line(v) + tolerance and its height above the ground B ((d - b) / a - v) / d is at most
// max_height; pixels below the band (beyond the ground) are dropped. Points with Z > max_range
// are left out.
LocalMap local_map(const SparseDisparity& map, const GroundLine& line, const Camera& camera,
                   const LocalMapParams& params);

// ---- grids --------------------------------------------------------------------------------
struct CellIndex {
    int x = 0;
    int z = 0;
    bool operator==(const CellIndex&) const = default;
};

// Cell of a ground-plane point (x, z) in metres: floor(x / size), floor(z / size).
CellIndex cell_of(const Eigen::Vector2d& point, double cell_size);

// A free-space ray of one frame, from the camera's cell to `end`.
struct Ray {
    CellIndex end;
    bool end_is_free = true;  // false: the ray stops at an obstacle, whose cell is not free
};

// The rays of one frame in the world plane: the bearings from `origin` are cut into bins of
// `bin_deg`; in each bin the ray ends just before the nearest obstacle point, or, without one,
// at the farthest ground point (free). Bins with neither get no ray.
std::vector<Ray> bearing_rays(const Eigen::Vector2d& origin,
                              const std::vector<Eigen::Vector2d>& obstacles,
                              const std::vector<Eigen::Vector2d>& ground, double cell_size,
                              double bin_deg);

enum class Cell : std::uint8_t { unknown = 0, free = 1, occupied = 2 };

// A window of cells: column i is cell x0 + i, row j is cell z0 + j.
struct DenseGrid {
    int x0 = 0;
    int z0 = 0;
    int width = 0;
    int height = 0;
    std::vector<Cell> cells;

    DenseGrid() = default;
    DenseGrid(int x0_, int z0_, int w, int h)
        : x0(x0_), z0(z0_), width(w), height(h), cells(static_cast<std::size_t>(w) * h) {}
    Cell at(int column, int row) const {
        return cells[static_cast<std::size_t>(row) * width + column];
    }
    Cell& at(int column, int row) { return cells[static_cast<std::size_t>(row) * width + column]; }
    std::size_t count(Cell state) const;
    bool operator==(const DenseGrid&) const = default;
};

// Accumulated evidence per cell: frames that saw it occupied (hits) and frames whose rays
// crossed it (misses). Occupied when hits >= 1 and hits >= misses; free when misses > hits;
// unknown without evidence. Unbounded (hashed), so the map grows with the path.
class EvidenceGrid {
  public:
    explicit EvidenceGrid(double cell_size);
    double cell_size() const { return cell_size_; }

    // One frame: every listed obstacle cell gets one hit; every cell on each ray from `origin`
    // to its end gets one miss, the end included only when it is free. Cells are counted once
    // per frame.
    void add_frame(const CellIndex& origin, const std::vector<CellIndex>& obstacles,
                   const std::vector<Ray>& rays);
    Cell state(const CellIndex& cell) const;
    bool occupied(const CellIndex& cell) const { return state(cell) == Cell::occupied; }
    bool empty() const { return cells_.empty(); }
    // The states over the bounding box of all cells with evidence and of `extra` cells, plus
    // `margin` cells on every side.
    DenseGrid to_dense(const std::vector<CellIndex>& extra = {}, int margin = 2) const;

  private:
    struct Evidence {
        int hits = 0;
        int misses = 0;
    };
    static std::int64_t key(const CellIndex& cell);
    double cell_size_;
    std::unordered_map<std::int64_t, Evidence> cells_;
};

// Cells of the digital line from a to b (Bresenham), both ends included.
std::vector<CellIndex> line_cells(const CellIndex& a, const CellIndex& b);

// One synchronous pass of the clean-up automaton over 8-neighbourhoods (outside = unknown):
//   rule 1, isolation: an occupied cell without an occupied neighbour becomes free when at least
//   one neighbour is free, else unknown;
//   rule 2, gap filling: a non-occupied cell whose two opposite neighbours (W-E, N-S, NW-SE or
//   NE-SW) are both occupied becomes occupied.
DenseGrid ca_clean(const DenseGrid& grid);

// ---- map merging --------------------------------------------------------------------------
struct MergeParams {
    int max_shift = 2;    // cells, in x and in z
    int angle_steps = 2;  // rotations -angle_steps .. +angle_steps
    double angle_step_deg = 0.5;
    int min_gain = 3;  // overlap cells the best placement must gain over no change
    // The gain must also exceed significance * sqrt(score + base score): chance coincidences
    // of noisy cells are Poisson-like counts (0 switches this gate off).
    double significance = 3.0;
    // The placed local map must land with at least this share of its cells on occupied map
    // cells: a correction is only trusted when the map confirms the local map (0 = off).
    double min_match = 0.5;
    // A best placement on the edge of the search window (|dx| or |dz| = max_shift, or |dtheta| =
    // angle_steps, where that range is not 0) is not applied: the optimum was not located, it
    // may lie outside the window (docs/slam.md).
    bool reject_edge = true;
};

struct MergeResult {
    int dx = 0;  // cells
    int dz = 0;
    int dtheta = 0;        // steps of angle_step_deg
    int score = 0;         // occupied cells of the chosen placement that are occupied in the map
    int base_score = 0;    // the same without correction
    int cells = 0;         // distinct cells of the chosen placement
    bool at_edge = false;  // the placement lies on the edge of the search window
    bool applied = false;
};

// Rotates the world-plane points by dtheta * step about `pivot` (x' = c x + s z, z' = -s x + c z
// relative to the pivot, i.e. a rotation about the camera's y axis), shifts them by
// (dx, dz) * cell size, and counts the distinct cells they fall in that the global grid holds as
// occupied. Every combination in the window is tried; the largest count wins, ties to the
// smallest |dx| + |dz| + |dtheta| and then to the first in (dtheta, dz, dx) order. Applied when
// it beats the uncorrected count by at least min_gain and the gates of MergeParams pass.
MergeResult best_placement(const EvidenceGrid& global, const std::vector<Eigen::Vector2d>& points,
                           const Eigen::Vector2d& pivot, const MergeParams& params);

// The correction of `result` as a 3-D transform of world points (rotation about the world y axis
// through the pivot, then the shift).
Eigen::Isometry3d merge_correction(const MergeResult& result, const Eigen::Vector2d& pivot,
                                   double cell_size, const MergeParams& params);

// ---- pictures -----------------------------------------------------------------------------
// The grid (unknown grey, free white, occupied black), x to the right and z up, `pixels` per
// cell, with trajectories (camera positions, x and z) drawn as polylines in their BGR colours;
// below it a strip with the legend (cell states, labelled paths), a metric scale bar and the
// axes.
struct Polyline {
    std::vector<Eigen::Vector2d> points;
    cv::Scalar colour;
    std::string label;  // shown in the legend when not empty
};
cv::Mat render_map(const DenseGrid& grid, double cell_size, const std::vector<Polyline>& paths,
                   int pixels = 4);

}  // namespace stereo::robot::slam
