#include "swell/bake/particles.h"

#include <algorithm>

namespace swell::bake {

std::string_view toString(ParticleKind kind) {
    switch (kind) {
    case ParticleKind::Water:
        return "water";
    case ParticleKind::Wall:
        return "wall";
    case ParticleKind::Dummy:
        return "dummy";
    }
    return "?";
}

void Particles::add(double px, double py, ParticleKind k) {
    x.push_back(px);
    y.push_back(py);
    vx.push_back(0.0);
    vy.push_back(0.0);
    p.push_back(0.0);
    n.push_back(0.0);
    kind.push_back(k);
}

void Particles::reserve(std::size_t count) {
    x.reserve(count);
    y.reserve(count);
    vx.reserve(count);
    vy.reserve(count);
    p.reserve(count);
    n.reserve(count);
    kind.reserve(count);
}

bool Particles::consistent() const {
    const std::size_t s = size();
    return y.size() == s && vx.size() == s && vy.size() == s && p.size() == s && n.size() == s &&
           kind.size() == s;
}

std::size_t Particles::count(ParticleKind k) const {
    return static_cast<std::size_t>(std::count(kind.begin(), kind.end(), k));
}

} // namespace swell::bake
