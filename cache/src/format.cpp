#include "format.h"

#include <cmath>
#include <stdexcept>
#include <xxhash.h>

namespace swell::cache::format {
namespace {

struct Section {
    std::size_t bytes;    ///< section length in bytes
    std::size_t elemSize; ///< element size for the shuffle and delta filters
    std::size_t stride;   ///< components per particle (delta is taken per component)
};

/// Record sections in file order (docs/cache-format.md, "Frame record").
std::vector<Section> sections(Encoding enc, std::uint64_t ns, std::uint64_t nsp) {
    if (enc == Encoding::Float32)
        return {{ns * 8, 4, 2}, {nsp * 16, 4, 4}};
    return {{ns * 4, 2, 2}, {nsp * 4, 2, 2}, {nsp * 8, 4, 2}};
}

/// Element-wise integer delta (mod 2^bits) with the given component stride.
template <class U>
void deltaSection(std::uint8_t* base, std::size_t n, std::size_t stride, bool inverse) {
    if (inverse) {
        for (std::size_t i = stride; i < n; ++i)
            putField<U>(base + i * sizeof(U),
                        static_cast<U>(getField<U>(base + i * sizeof(U)) +
                                       getField<U>(base + (i - stride) * sizeof(U))));
    } else {
        for (std::size_t i = n; i-- > stride;)
            putField<U>(base + i * sizeof(U),
                        static_cast<U>(getField<U>(base + i * sizeof(U)) -
                                       getField<U>(base + (i - stride) * sizeof(U))));
    }
}

std::uint16_t quantize(float v, float lo, float hi) {
    const double t = (static_cast<double>(v) - lo) / (static_cast<double>(hi) - lo);
    return static_cast<std::uint16_t>(std::lround(t * 65535.0));
}

float dequantize(std::uint16_t q, float lo, float hi) {
    return static_cast<float>(lo + (static_cast<double>(hi) - lo) * (q / 65535.0));
}

/// memcpy that accepts empty ranges (whose pointers may be null).
void copyBytes(void* dst, const void* src, std::size_t n) {
    if (n)
        std::memcpy(dst, src, n);
}

} // namespace

std::uint64_t rawRecordSize(Encoding enc, std::uint64_t ns, std::uint64_t nsp) {
    return enc == Encoding::Float32 ? ns * 8 + nsp * 16 : ns * 4 + nsp * 12;
}

void encodeRecord(const Header& h, const Frame& f, std::vector<std::uint8_t>& out) {
    const std::size_t ns = f.surfaceCount(), nsp = f.splashCount();
    out.resize(rawRecordSize(h.encoding, ns, nsp));
    if (h.encoding == Encoding::Float32) {
        copyBytes(out.data(), f.surface.data(), ns * 8);
        copyBytes(out.data() + ns * 8, f.splash.data(), nsp * 16);
        return;
    }
    const Domain& d = h.domain;
    std::uint8_t* p = out.data();
    for (std::size_t i = 0; i < ns; ++i, p += 4) {
        putField(p, quantize(f.surface[2 * i], d.xMin, d.xMax));
        putField(p + 2, quantize(f.surface[2 * i + 1], d.yMin, d.yMax));
    }
    for (std::size_t i = 0; i < nsp; ++i, p += 4) {
        putField(p, quantize(f.splash[4 * i], d.xMin, d.xMax));
        putField(p + 2, quantize(f.splash[4 * i + 1], d.yMin, d.yMax));
    }
    for (std::size_t i = 0; i < nsp; ++i, p += 8) {
        putField(p, f.splash[4 * i + 2]);
        putField(p + 4, f.splash[4 * i + 3]);
    }
}

Frame decodeRecord(const Header& h, std::span<const std::uint8_t> raw, std::uint32_t ns,
                   std::uint32_t nsp) {
    Frame f;
    f.surface.resize(std::size_t{ns} * 2);
    f.splash.resize(std::size_t{nsp} * 4);
    if (h.encoding == Encoding::Float32) {
        copyBytes(f.surface.data(), raw.data(), std::size_t{ns} * 8);
        copyBytes(f.splash.data(), raw.data() + std::size_t{ns} * 8, std::size_t{nsp} * 16);
        return f;
    }
    const Domain& d = h.domain;
    const std::uint8_t* p = raw.data();
    for (std::size_t i = 0; i < ns; ++i, p += 4) {
        f.surface[2 * i] = dequantize(getField<std::uint16_t>(p), d.xMin, d.xMax);
        f.surface[2 * i + 1] = dequantize(getField<std::uint16_t>(p + 2), d.yMin, d.yMax);
    }
    for (std::size_t i = 0; i < nsp; ++i, p += 4) {
        f.splash[4 * i] = dequantize(getField<std::uint16_t>(p), d.xMin, d.xMax);
        f.splash[4 * i + 1] = dequantize(getField<std::uint16_t>(p + 2), d.yMin, d.yMax);
    }
    for (std::size_t i = 0; i < nsp; ++i, p += 8) {
        f.splash[4 * i + 2] = getField<float>(p);
        f.splash[4 * i + 3] = getField<float>(p + 4);
    }
    return f;
}

void shuffle(Encoding enc, std::uint32_t ns, std::uint32_t nsp, std::span<const std::uint8_t> in,
             std::vector<std::uint8_t>& out, bool inverse) {
    out.resize(in.size());
    std::size_t base = 0;
    for (const Section& s : sections(enc, ns, nsp)) {
        const std::size_t n = s.bytes / s.elemSize;
        // Forward: element e, byte b -> plane b, position e. Inverse swaps roles.
        for (std::size_t b = 0; b < s.elemSize; ++b)
            for (std::size_t e = 0; e < n; ++e) {
                const std::size_t interleaved = base + e * s.elemSize + b;
                const std::size_t planar = base + b * n + e;
                if (inverse)
                    out[interleaved] = in[planar];
                else
                    out[planar] = in[interleaved];
            }
        base += s.bytes;
    }
}

void delta(Encoding enc, std::uint32_t ns, std::uint32_t nsp, std::span<std::uint8_t> data,
           bool inverse) {
    std::size_t base = 0;
    for (const Section& s : sections(enc, ns, nsp)) {
        const std::size_t n = s.bytes / s.elemSize;
        if (s.elemSize == 2)
            deltaSection<std::uint16_t>(data.data() + base, n, s.stride, inverse);
        else
            deltaSection<std::uint32_t>(data.data() + base, n, s.stride, inverse);
        base += s.bytes;
    }
}

std::uint64_t checksum(const void* data, std::size_t size) {
    return XXH3_64bits(data, size);
}

std::uint64_t headerChecksum(std::span<const std::uint8_t> head) {
    XXH3_state_t* st = XXH3_createState();
    if (!st)
        throw std::bad_alloc();
    XXH3_64bits_reset(st);
    XXH3_64bits_update(st, head.data(), kOffHeaderChecksum);
    XXH3_64bits_update(st, head.data() + kFixedHeaderSize, head.size() - kFixedHeaderSize);
    const std::uint64_t h = XXH3_64bits_digest(st);
    XXH3_freeState(st);
    return h;
}

} // namespace swell::cache::format
