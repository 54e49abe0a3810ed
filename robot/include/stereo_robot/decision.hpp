// The direction decisions of thesis Sec. 4.1: the threshold algorithm and the fuzzy one.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "stereo/image.hpp"
#include "stereo_robot/windows.hpp"

namespace stereo::robot {

enum class Direction { forward, left, right, backwards };

std::string to_string(Direction direction);

// The side window with the larger free distance (WindowStats::free_disparity at `rate`: the
// smaller free disparity), or nothing when both are equal. Both methods never turn towards the
// other side (issue 50, docs/avoidance.md "Safety").
std::optional<Direction> freer_side(const std::array<WindowStats, 3>& stats, double rate);

// ---- threshold algorithm (Sec. 4.1.1) --------------------------------------------------------
struct ThresholdParams {
    double rate =
        0.20;  // r: largest occupied fraction of the centre window that still goes straight
    int border = kDefaultBorder;
};

struct ThresholdDecision {
    Direction direction = Direction::forward;
    // (avD2 - avD1) / avD2 for a turn (avD1 the chosen side's mean, at least 0); 0 when going
    // straight.
    double certainty = 0.0;
    bool safety_override = false;  // the mean-disparity rule chose the side with less free room
    std::array<WindowStats, 3> stats{};
    std::array<double, 3> mean{};  // mean valid disparity per window (ndisp when none is valid)
};

// Centre occupancy below `rate` -> forward; otherwise the side with the smaller mean disparity
// (ties go left), unless the other side has the larger free distance (freer_side), which then
// wins. `ndisp` stands in for the mean of a window with no valid pixel.
ThresholdDecision decide_threshold(const DisparityMap& map, double threshold, int ndisp,
                                   const ThresholdParams& params = {},
                                   const GroundModel* ground = nullptr);

// ---- fuzzy algorithm (Sec. 4.1.3) ------------------------------------------------------------
struct Gaussian {
    double centre = 0.0;
    double sigma = 1.0;
    double operator()(double x) const;  // exp(-(x - c)^2 / (2 s^2))
};

struct FisParams {
    Gaussian free{0.0, 0.065};     // input MF, all three windows
    Gaussian occupied{1.0, 0.25};  // input MF, all three windows
    Gaussian left{-19.0, 5.5};     // output angle MF (degrees, negative = left)
    Gaussian forward{0.0, 12.5};
    Gaussian right{19.0, 5.5};
    Gaussian backwards_yes{0.85, 0.23};  // output "move backwards" MF on [0, 1]
    double angle_min = -30.0;            // the camera's 60 degree field of view
    double angle_max = 30.0;
    double angle_step = 0.01;  // centroid grid
    double backwards_step = 0.001;
    double backwards_threshold = 0.65;  // back off above this
    // |angle| <= this is "no turn": forward when the centre is free, else the default rule
    // (below) decides. 1 degree: see docs/avoidance.md (the thesis counts a 9-degree output as
    // a turn).
    double forward_band = 1.0;
    // Safety rate r (the threshold method's): a centre occupancy >= rate is "blocked" and never
    // gives "forward".
    double rate = 0.20;
};

struct FisResult {
    double angle_deg = 0.0;  // the Mamdani centroid, or the default rule's turn angle
    double backwards = 0.0;
    Direction decision = Direction::forward;
    std::array<double, 4> firing{};  // rule strengths: forward, left, right, backwards
    double mamdani_angle_deg = 0.0;  // the centroid of rules 1-3 alone
    bool default_rule = false;       // rule 5 decided (blocked centre, no decisive turn)
};

// Throws std::invalid_argument unless every input is a number in [0, 1].
void check_fraction(double value, const std::string& name);

// Mamdani FIS: min for AND and implication, max aggregation, centroid over the grids; an empty
// aggregated set defuzzifies to the midpoint of its range. The decision (docs/avoidance.md):
//   backwards when backwards > backwards_threshold;
//   else a turn by the angle's sign when |angle| > forward_band and that side's turn rule fires
//   (strength at least the turn MF at the inner edge of the opposite third of the angle range,
//   9.2e-7 with the defaults: below it the clipped set is flat over the other side's sector);
//   else forward when centre < rate;
//   else (rule 5, the default rule: a blocked centre and no turn rule decisive) a turn to the
//   freer side (smaller occupancy, ties left), or backwards when that side is blocked as well;
//   the reported angle is then the centroid of that side's whole output MF.
// So "forward" implies centre < rate for every input (tests/test_robot.cpp checks a grid).
FisResult evaluate_fis(double left, double centre, double right, const FisParams& params = {});

// The fuzzy decision on a disparity map: window occupancies at `threshold`, then evaluate_fis.
// A turn of the FIS towards the side with the smaller free distance (freer_side) is replaced by
// a turn the other way (angle: that side's whole-MF centroid), or by backwards when that side is
// blocked as well (occupancy >= rate); safety_override says so.
struct FuzzyDecision {
    FisResult fis;
    std::array<WindowStats, 3> stats{};
    bool safety_override = false;
};
FuzzyDecision decide_fuzzy(const DisparityMap& map, double threshold, const FisParams& params = {},
                           int border = kDefaultBorder, const GroundModel* ground = nullptr);

}  // namespace stereo::robot
