#include "swell/cache/header.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace swell::cache {

float Header::maxPositionError() const {
    if (encoding == Encoding::Float32)
        return 0.0f;
    // Half a quantization step per axis, plus float32 rounding of the decoded value.
    const double halfStep = 0.5 *
                            std::max(static_cast<double>(domain.xMax) - domain.xMin,
                                     static_cast<double>(domain.yMax) - domain.yMin) /
                            65535.0;
    const double mag = std::max({std::fabs(domain.xMin), std::fabs(domain.xMax),
                                 std::fabs(domain.yMin), std::fabs(domain.yMax)});
    const double rounding = mag * std::numeric_limits<float>::epsilon();
    return static_cast<float>(halfStep + rounding);
}

} // namespace swell::cache
