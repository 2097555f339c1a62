#pragma once
// GPU time of each stage of one timed frame, from GL timestamp queries (milliseconds). One type
// for the replay passes of every mode and the render passes; a stage a frame skips reads 0.

namespace swell::runtime {

struct StageTimes {
    double sliceLookupMs = 0.0; ///< eq. (5)-(6), every slice set (slice_lookup.comp)
    double reconstructMs = 0.0; ///< eq. (7) (surging, each ripple direction; not whirlpool)
    double synthesisMs = 0.0;   ///< eq. (8), ripple with a synthesis pass
    double spiralMs = 0.0;      ///< spiral prefix sums and mapping, whirlpool
    double skyMs = 0.0;         ///< render: environment background
    double waterMs = 0.0;       ///< render: height-field mesh and sides
    double splashMs = 0.0;      ///< render: point sprites (0 when no splash pass ran)
    double resolveMs = 0.0;     ///< render: multisample resolve

    StageTimes& operator+=(const StageTimes& o) {
        sliceLookupMs += o.sliceLookupMs;
        reconstructMs += o.reconstructMs;
        synthesisMs += o.synthesisMs;
        spiralMs += o.spiralMs;
        skyMs += o.skyMs;
        waterMs += o.waterMs;
        splashMs += o.splashMs;
        resolveMs += o.resolveMs;
        return *this;
    }
    /// Every stage divided by n (means of sums over n frames); n = 0 gives zeros.
    StageTimes mean(int n) const {
        StageTimes t;
        if (n <= 0)
            return t;
        const double k = 1.0 / n;
        t.sliceLookupMs = sliceLookupMs * k;
        t.reconstructMs = reconstructMs * k;
        t.synthesisMs = synthesisMs * k;
        t.spiralMs = spiralMs * k;
        t.skyMs = skyMs * k;
        t.waterMs = waterMs * k;
        t.splashMs = splashMs * k;
        t.resolveMs = resolveMs * k;
        return t;
    }
};

} // namespace swell::runtime
