// The loops the references share: every cell of a volume, every pixel of a 3x3 neighbourhood.
// Written plainly, with no incremental tricks, like the references themselves.
#pragma once

namespace stereo::reference {

// visit(x, y, d) for every cell of a width x height x ndisp volume, plane by plane.
template <class Visit>
void for_each_cell(int width, int height, int ndisp, Visit visit) {
    for (int d = 0; d < ndisp; ++d) {
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                visit(x, y, d);
            }
        }
    }
}

// visit(i, j) for the 3x3 offsets around a centre, the centre included.
template <class Visit>
void for_each_offset3x3(Visit visit) {
    for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
            visit(i, j);
        }
    }
}

}  // namespace stereo::reference
