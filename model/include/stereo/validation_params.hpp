// What stage 6 is asked to do (ValidationParams) and where a result is valid at all
// (InvalidBorder): the small types the stages share with the scheduler (pipeline.hpp), so that a
// stage's header need not include the scheduler's.
#pragma once

namespace stereo {

// The validation stages after the winner takes all (docs/fixed-point.md stage 6). Each can be
// switched off; all are off by default here, so the API's default is the plain winner. The
// ratio and tolerance are what `stereo match` uses (its stages are on unless --no-validation):
// chosen on all eight scenes with ground truth (docs/results.md, "Validated output").
struct ValidationParams {
    bool uniqueness = false;  // invalid when C1 * (100 + ratio) >= C2 * 100
    int uniqueness_ratio = 20;
    bool left_right = false;  // invalid when |dL(x) - dR(x - dL(x))| > tolerance
    int lr_tolerance = 0;
    bool subpixel = false;  // parabola through the costs at d - 1, d, d + 1
    bool operator==(const ValidationParams&) const = default;

    // Every stage on, with the ratio and tolerance above.
    static ValidationParams all_on() { return {true, 20, true, 0, true}; }
};

// Which outputs are valid. `reach` is how far a result looks from its pixel: the aggregation
// radius, plus one for the 3x3 CA neighbourhoods. A pixel is valid when everything its winning
// disparity d depends on lies inside both images: the window stays inside the image
// (reach <= x < width - reach, reach <= y < height - reach) and its right-image samples do too
// (reach <= x - d < width - reach; the upper bound matters for negative d only).
struct InvalidBorder {
    int reach = 0;
    bool window_inside(int x, int y, int width, int height) const {
        return x >= reach && x < width - reach && y >= reach && y < height - reach;
    }
    bool valid(int x, int y, int d, int width, int height) const {
        return window_inside(x, y, width, height) && x - d >= reach && x - d < width - reach;
    }
};

}  // namespace stereo
