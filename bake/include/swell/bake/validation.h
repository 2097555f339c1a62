#pragma once
#include <span>
#include <vector>

#include "swell/bake/particles.h"

namespace swell::bake {

/// One experimental point of the dam-break surge front: T = t sqrt(2 g / a), Z = z / a.
struct FrontPoint {
    double T = 0.0;
    double Z = 0.0;
};

/// Martin & Moyce (1952), "Part IV. An experimental study of the collapse of liquid
/// columns on a rigid horizontal plane", Phil. Trans. R. Soc. Lond. A 244, 312-324,
/// Fig. 3, column of height 2a (n^2 = 2): surge front Z against T for a = 2.25 in.
/// Values as digitised in PySPH (pysph/examples/db_exp_data.py, "mm_data_2").
std::span<const FrontPoint> martinMoyceA225();
/// Same figure and source, a = 1.125 in ("mm_data_1").
std::span<const FrontPoint> martinMoyceA1125();

/// Surge front: the largest x of a water particle that is not splash (n >= d1 n0,
/// paper eq. (4)), minus `x0` (the column's back face). Returns 0 if none qualifies.
double surgeFront(const Particles& particles, double n0, double splashRatio, double x0 = 0.0);

/// Mean and max of |Z_sim(T) - Z_exp(T)| over the experimental points with T in [tLo, tHi];
/// Z_sim is linearly interpolated in a simulated series sorted by T.
struct FrontError {
    double mean = 0.0;
    double max = 0.0;
    double meanSigned = 0.0; ///< mean of Z_sim - Z_exp (positive: simulation ahead)
    int points = 0;
};
FrontError compareFront(std::span<const FrontPoint> simulated,
                        std::span<const FrontPoint> experiment, double tLo, double tHi);

/// Least-squares fit v(t) ~ a cos(omega t) + b sin(omega t) + c of a gauge record at a
/// known angular frequency (regular-wave validation): amplitude sqrt(a^2 + b^2) and phase
/// atan2(b, a), so v ~ amplitude cos(omega t - phase) + mean. Throws std::invalid_argument
/// for fewer than 3 samples, different lengths or a singular fit.
struct HarmonicFit {
    double amplitude = 0.0; ///< (units of v)
    double phase = 0.0;     ///< (rad), in (-pi, pi]
    double mean = 0.0;      ///< (units of v)
};
HarmonicFit fitHarmonic(std::span<const double> t, std::span<const double> v, double omega);

} // namespace swell::bake
