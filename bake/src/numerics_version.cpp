#include "swell/bake/numerics_version.h"

#include "parallel_thresholds.h"

namespace swell::bake {

static_assert(kParallelMin <= kParallelVector, "the smallest parallel floating-point reduction");

bool threadCountAffectsResults(std::size_t particles) {
    return particles >= kParallelMin;
}

} // namespace swell::bake
