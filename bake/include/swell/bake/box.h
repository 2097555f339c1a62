#pragma once

#include <algorithm>

namespace swell::bake {

/// An axis-aligned rectangle [x0, x1] x [y0, y1] in metres.
struct Box {
    double x0 = 0.0;
    double y0 = 0.0;
    double x1 = 0.0;
    double y1 = 0.0;

    double width() const { return x1 - x0; }
    double height() const { return y1 - y0; }
    bool contains(double x, double y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
    /// Whether `o` and this box share an area (more than 1e-9 m on both axes); boxes that only
    /// touch do not.
    bool overlaps(const Box& o) const {
        return std::min(x1, o.x1) - std::max(x0, o.x0) > 1e-9 &&
               std::min(y1, o.y1) - std::max(y0, o.y0) > 1e-9;
    }
};

} // namespace swell::bake
