// The plane field as a streaming core computes it (issue 45; docs/hierarchical.md, "Hardware
// form of the field"). The plane fit of FieldModel::plane needs every full-level winner of a frame
// before the frame's 1-D pass can start, and iterates. A streaming core cannot wait for that, so it
// splits the fit between frames:
//  - during frame t the core runs its 1-D pass along the field of the plane it was given, and
//    gathers PlaneStatistics over frame t's full level: the inlier sums of that same plane's
//    least-squares fit and the histogram of the valid offsets;
//  - after frame t the host (PlaneTracker) solves the fit from those sums and gives the core the
//    plane of frame t + 1.
// On a rig whose misalignment does not change, each frame performs one iteration of
// vertical_plane's fit, so the plane reaches vertical_plane's after as many frames as it iterates.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "stereo/hierarchical.hpp"

namespace stereo::hierarchical {

// Inlier tolerances of the fit in 1/kPlaneOne pixel: the first fit takes the offsets within 2 of
// the most frequent one, every later fit those within 1.5 of the previous plane.
inline constexpr std::int64_t kFirstFitTolerance = 2 * kPlaneOne;
inline constexpr std::int64_t kFitTolerance = 3 * kPlaneOne / 2;

// What the core is given for a frame: the plane its pass follows and the inlier tolerance of the
// statistics it gathers.
struct PlaneSetting {
    Plane plane;
    std::int64_t tolerance = kFirstFitTolerance;
    bool operator==(const PlaneSetting&) const = default;
};

// Whether a vote at (x, y) (the right image's column, right_column) with offset v is an inlier of
// the setting's plane.
bool is_plane_inlier(int x, int y, int v, const PlaneSetting& setting);

// One frame's statistics over the votes of the full level's valid winners (right_column: a winner
// at (x, y) with displacement (d, v) votes at the right pixel (xr, y), xr = x - d; none when xr is
// outside the image). Inliers: votes with |v kPlaneOne - (a + b xr + c y)| <= tolerance. The sums
// are exact integers (the normal equations of v = a + b xr + c y over the inliers); sum_x, sum_xx,
// sum_xy and sum_xv are over xr.
struct PlaneStatistics {
    std::int64_t count = 0;  // inliers
    std::int64_t sum_x = 0;
    std::int64_t sum_y = 0;
    std::int64_t sum_xx = 0;
    std::int64_t sum_xy = 0;
    std::int64_t sum_yy = 0;
    std::int64_t sum_v = 0;
    std::int64_t sum_xv = 0;
    std::int64_t sum_yv = 0;
    int v_min = 0;                        // the offset of histogram[0]
    std::vector<std::int64_t> histogram;  // valid winners per offset v_min, v_min + 1, ...
    bool operator==(const PlaneStatistics&) const = default;
};

// The statistics of `level` (the full level's map) for `setting`; the histogram spans the
// full-size range [v_min, v_max].
PlaneStatistics plane_statistics(const LevelMap& level, const PlaneSetting& setting, int v_min,
                                 int v_max);

// The most frequent offset of the histogram; ties go to the smaller |v|, then the smaller v;
// 0 when it is empty.
int histogram_mode(const PlaneStatistics& statistics);

// The least-squares plane of the statistics' inliers, rounded to 1/kPlaneOne; std::nullopt when
// they are fewer than 3 or collinear. (vertical_plane solves each of its fits with this.)
std::optional<Plane> solve_plane(const PlaneStatistics& statistics);

// The host's side: the setting of the next frame from each frame's statistics.
//  - Start (after construction or restart): the plane 0 and the first-fit tolerance.
//  - After a start frame: the constant plane at the histogram's mode, first-fit tolerance.
//  - After any other frame: the solved plane and the fit tolerance; when the fit fails (too few
//    or collinear inliers), a new start from that frame's mode.
class PlaneTracker {
  public:
    [[nodiscard]] const PlaneSetting& setting() const { return setting_; }
    void update(const PlaneStatistics& frame);
    void restart();

  private:
    PlaneSetting setting_{};
    bool from_mode_ = true;  // the next update takes the mode (a start frame)
};

// The hardware form of Output::vertical_field on one frame: the three levels, the 1-D pass along
// plane_field(setting.plane) with stage 6, and the statistics the next frame's setting comes from.
struct FrameResult {
    Result result;  // as match's, with `field` the plane's field
    PlaneStatistics statistics;
};
FrameResult match_frame(const Image& left, const Image& right, const Params& params,
                        const PlaneSetting& setting);

}  // namespace stereo::hierarchical
