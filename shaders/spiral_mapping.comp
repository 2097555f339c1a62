#version 450 core
// Whirlpool (Sec. 4.5), pass 2 of 2 per frame: the J = 2K - 1 slices, sampled by eq. (5)-(6)
// (slice_lookup.comp), are bent into log spirals r(t) = a e^(b t) at angle phi_j + t,
// t in [0, 2 pi], with phi_j = 2 pi j / J + spin(tau). A cell at polar (r, theta) about the
// centre lies at spiral parameter t = ln(r / a) / b (clamped to [0, 2 pi]) and slice coordinate
// s = (theta - t - spin) J / (2 pi) mod J; the cache's x runs along the spiral, column
// coordinate u = N t / (2 pi). Its height is the box mean over the cell's footprint
// (whirlpool.h) of the spirals linear between neighbours (across, w slices) and each profile
// linear between column centres (along, wu columns): with F(x, v) the integral of that
// surface from (0, 0) to slice coordinate x and profile coordinate v = u - 1/2,
//     h = [F(s1, v1) - F(s1, v0) - F(s0, v1) + F(s0, v0)] / (w wu),
// s0,1 = s -+ w / 2 and v0,1 = v -+ wu / 2. F comes from spiral_prefix.comp's tables of the
// spirals' integrals (double), so a cell costs the same whatever its footprint. Minus the eye
// funnel's depth. Per cell the geometry (v, wu, s at spin 0, w, funnel) is precomputed on the
// CPU in double.
layout(local_size_x = 64) in;

struct Cell {
    float v;   // profile coordinate u - 1/2 (column centres at integers)
    float wu;  // footprint width along the profile, columns, >= 1
    float s;   // slice coordinate at spin 0, in [0, J)
    float w;   // footprint width across the spirals, slices, in [1, J]
    float dip; // eye funnel depth, metres
    float pad0;
    float pad1;
    float pad2;
};

layout(std430, binding = 2) readonly buffer Cells { Cell cells[]; };     // m * N + n
layout(std430, binding = 3) writeonly buffer Heights { float heights[]; }; // m * N + n
layout(std430, binding = 5) readonly buffer Along { dvec2 along[]; };    // (C, p), j * N + k
layout(std430, binding = 6) readonly buffer Across { dvec2 across[]; };  // (T, P), j <= J

uniform int u_cells;       // N * M
uniform int u_N;           // columns of the profile
uniform int u_J;           // slices, 2K - 1
uniform float u_spin;      // spin(tau) in slice units, in [0, J)
uniform float u_reference; // level added back (columns are relative)

// An integral q (q.x at column centres, q.y its derivative there; spiral_prefix.comp's tables)
// continued to profile coordinate v, linear between column centres and constant beyond the
// end ones. Row j, column k at j * N + k.
#define CONTINUED(table, j, v, out)                                                   \
    {                                                                                  \
        int row_ = (j) * u_N;                                                          \
        if ((v) <= 0.0) {                                                              \
            out = (v) * table[row_].y;                                                 \
        } else if ((v) >= double(u_N - 1)) {                                           \
            dvec2 q_ = table[row_ + u_N - 1];                                          \
            out = q_.x + ((v) - double(u_N - 1)) * q_.y;                               \
        } else {                                                                       \
            int k_ = int(floor(v));                                                    \
            double a_ = (v) - double(k_);                                              \
            dvec2 q_ = table[row_ + k_];                                               \
            out = q_.x + a_ * q_.y + 0.5 * a_ * a_ * (table[row_ + k_ + 1].y - q_.y); \
        }                                                                              \
    }

double alongAt(int j, double v) {
    double c;
    CONTINUED(along, j, v, c)
    return c;
}

double acrossAt(int j, double v) {
    double t;
    CONTINUED(across, j, v, t)
    return t;
}

// F(x, v): across the spirals the trapezoid sum T to row j plus the part of the interval
// [j, j + 1) up to x, whole turns of the periodic slice axis adding row J's total.
double integral(double x, double v) {
    double turns = floor(x / double(u_J));
    double y = x - turns * double(u_J);
    int j = min(int(floor(y)), u_J - 1);
    double a = y - double(j);
    double here = alongAt(j, v);
    double f = acrossAt(j, v) + a * here + 0.5 * a * a * (alongAt(j + 1, v) - here);
    if (turns != 0.0) f += turns * acrossAt(u_J, v);
    return f;
}

void main() {
    int c = int(gl_GlobalInvocationID.x);
    if (c >= u_cells) return;
    Cell cell = cells[c];
    double s = double(cell.s) - double(u_spin);
    if (s < 0.0) s += double(u_J);
    double s0 = s - 0.5 * double(cell.w);
    double s1 = s + 0.5 * double(cell.w);
    double v0 = double(cell.v) - 0.5 * double(cell.wu);
    double v1 = double(cell.v) + 0.5 * double(cell.wu);
    double box = (integral(s1, v1) - integral(s1, v0)) - (integral(s0, v1) - integral(s0, v0));
    heights[c] = float(box / (double(cell.w) * double(cell.wu))) + u_reference - cell.dip;
}
