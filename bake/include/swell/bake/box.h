#pragma once

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
};

} // namespace swell::bake
