// image_probe: small image checks for the end-to-end window tests (tests/preview_check.sh), which
// have only a shell: pixel differences between two PNGs, statistics and the bright-region centroid
// of a rectangle, and bit-exact comparison of two EXRs' channels.
//   image_probe diff A.png B.png          max |A-B| over A's size (B cropped at its top-left),
//                                         and the fraction of pixels that differ
//   image_probe stats IMG x0 y0 x1 y1     mean and standard deviation of luma (0..255)
//   image_probe centroid IMG x0 y0 x1 y1  centroid of the pixels brighter than halfway between
//                                         the rectangle's darkest and brightest luma
//   image_probe colour IMG RRGGBB x0 y0 x1 y1
//                                         centroid and count of the pixels of exactly that colour
//                                         (the overlay's markers: drawn as exact bytes)
//   image_probe exr-equal A.exr B.exr     exit 0 when every channel of A is in B, bit for bit
//   image_probe exr-channels A.exr        each float channel, sorted by name: "name min max"
//                                         (non-finite values counted as "nonfinite N")
//   image_probe exr-relmse A.exr B.exr [R X Y ...]
//                                         relMSE of A against B (the experiments' ε), whole image,
//                                         and the mean over discs of radius R px at each (X, Y):
//                                         two references of different seeds give twice the
//                                         noise either holds (docs/foveation-study.md)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <stb/stb_image.h>

#include "io/exr.h"
#include "metrics/image_metrics.h"

namespace {

struct Image {
    int w = 0, h = 0;
    std::vector<unsigned char> rgb;
    float Luma(int x, int y) const {
        const unsigned char* p = &rgb[3 * (size_t(y) * size_t(w) + size_t(x))];
        return 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
    }
};

Image Load(const char* path) {
    Image img;
    int n = 0;
    unsigned char* data = stbi_load(path, &img.w, &img.h, &n, 3);
    if (!data) {
        std::fprintf(stderr, "image_probe: cannot read %s\n", path);
        std::exit(2);
    }
    img.rgb.assign(data, data + size_t(img.w) * size_t(img.h) * 3);
    stbi_image_free(data);
    return img;
}

int Diff(const char* a, const char* b) {
    Image A = Load(a), B = Load(b);
    if (B.w < A.w || B.h < A.h) {
        std::printf("size %dx%d vs %dx%d\n", A.w, A.h, B.w, B.h);
        return 1;
    }
    int maxDiff = 0;
    size_t differing = 0;
    for (int y = 0; y < A.h; ++y)
        for (int x = 0; x < A.w; ++x) {
            int d = 0;
            for (int c = 0; c < 3; ++c)
                d = std::max(d, std::abs(int(A.rgb[3 * (size_t(y) * A.w + x) + c]) -
                                         int(B.rgb[3 * (size_t(y) * B.w + x) + c])));
            maxDiff = std::max(maxDiff, d);
            differing += d > 0;
        }
    std::printf("max=%d differing=%.6f\n", maxDiff, double(differing) / (double(A.w) * A.h));
    return 0;
}

int Stats(const char* path, int x0, int y0, int x1, int y1) {
    Image img = Load(path);
    double sum = 0, sum2 = 0, n = 0;
    for (int y = y0; y < std::min(y1, img.h); ++y)
        for (int x = x0; x < std::min(x1, img.w); ++x) {
            const double l = img.Luma(x, y);
            sum += l;
            sum2 += l * l;
            n += 1;
        }
    const double mean = n ? sum / n : 0.0;
    std::printf("mean=%.3f std=%.3f\n", mean, n ? std::sqrt(std::max(0.0, sum2 / n - mean * mean)) : 0.0);
    return 0;
}

// Prints the centre of the pixels in [x0, x1) × [y0, y1) that `selected(x, y)` picks ("none" and
// 1 when none is); with `count`, also how many there are.
template <class Selected>
int PrintCentroid(const Image& img, int x0, int y0, int x1, int y1, bool count, Selected&& selected) {
    double sx = 0, sy = 0, n = 0;
    for (int y = y0; y < std::min(y1, img.h); ++y)
        for (int x = x0; x < std::min(x1, img.w); ++x)
            if (selected(x, y)) {
                sx += x + 0.5;
                sy += y + 0.5;
                n += 1;
            }
    if (n == 0) {
        std::printf("none\n");
        return 1;
    }
    if (count) std::printf("%.1f %.1f %d\n", sx / n, sy / n, int(n));
    else std::printf("%.1f %.1f\n", sx / n, sy / n);
    return 0;
}

// The centre of the box's bright pixels (luma above the middle of its range).
int Centroid(const char* path, int x0, int y0, int x1, int y1) {
    Image img = Load(path);
    float lo = 1e9f, hi = -1e9f;
    for (int y = y0; y < std::min(y1, img.h); ++y)
        for (int x = x0; x < std::min(x1, img.w); ++x) {
            lo = std::min(lo, img.Luma(x, y));
            hi = std::max(hi, img.Luma(x, y));
        }
    const float mid = 0.5f * (lo + hi);
    return PrintCentroid(img, x0, y0, x1, y1, false, [&](int x, int y) { return img.Luma(x, y) > mid; });
}

// The centre and count of the box's pixels of exactly colour `hex` (RRGGBB).
int ColourCentroid(const char* path, const char* hex, int x0, int y0, int x1, int y1) {
    Image img = Load(path);
    const unsigned long rgb = std::strtoul(hex, nullptr, 16);
    return PrintCentroid(img, x0, y0, x1, y1, true, [&](int x, int y) {
        const unsigned char* p = &img.rgb[3 * (size_t(y) * size_t(img.w) + size_t(x))];
        return (unsigned long)((p[0] << 16) | (p[1] << 8) | p[2]) == rgb;
    });
}

int ExrChannels(const char* path) {
    const fovrt::ExrImage image = fovrt::ReadExr(path);
    for (const auto& [name, data] : image.channels) {  // a std::map: sorted by name
        if (!image.Has(name) || data.floats.empty()) continue;
        float lo = INFINITY, hi = -INFINITY;
        size_t nonFinite = 0;
        for (float v : data.floats) {
            if (!std::isfinite(v)) {
                ++nonFinite;
                continue;
            }
            lo = std::min(lo, v), hi = std::max(hi, v);
        }
        std::printf("%s %g %g", name.c_str(), lo, hi);
        if (nonFinite) std::printf(" nonfinite %zu", nonFinite);
        std::printf("\n");
    }
    return 0;
}

int ExrEqual(const char* a, const char* b) {
    const fovrt::ExrImage A = fovrt::ReadExr(a), B = fovrt::ReadExr(b);
    if (A.width != B.width || A.height != B.height) {
        std::printf("size differs\n");
        return 1;
    }
    for (const auto& [name, data] : A.channels) {
        auto it = B.channels.find(name);
        if (it == B.channels.end()) {
            std::printf("channel %s missing in %s\n", name.c_str(), b);
            return 1;
        }
        const bool same = data.isUint ? data.uints == it->second.uints
                                      : data.floats.size() == it->second.floats.size() &&
                                            std::memcmp(data.floats.data(), it->second.floats.data(),
                                                        data.floats.size() * sizeof(float)) == 0;
        if (!same) {
            std::printf("channel %s differs\n", name.c_str());
            return 1;
        }
    }
    std::printf("equal (%zu channels)\n", A.channels.size());
    return 0;
}

int ExrRelMse(int argc, char** argv) {
    const fovrt::Plane<fovrt::vec3> a = fovrt::ReadRgbExr(argv[2]), b = fovrt::ReadRgbExr(argv[3]);
    if (a.width() != b.width() || a.height() != b.height()) {
        std::printf("size differs\n");
        return 1;
    }
    std::printf("whole %.6g\n", fovrt::RelMse(a, b));
    if (argc < 7) return 0;
    const float r = std::strtof(argv[4], nullptr);
    double sum = 0.0;
    int discs = 0;
    for (int i = 5; i + 1 < argc; i += 2, ++discs) {
        const float cx = std::strtof(argv[i], nullptr), cy = std::strtof(argv[i + 1], nullptr);
        fovrt::Plane<uint8_t> mask(a.width(), a.height());
        for (int y = 0; y < a.height(); ++y)
            for (int x = 0; x < a.width(); ++x)
                mask(x, y) = (x + 0.5f - cx) * (x + 0.5f - cx) + (y + 0.5f - cy) * (y + 0.5f - cy) <= r * r;
        sum += fovrt::RelMse(a, b, &mask);
    }
    std::printf("discs %d radius %g mean %.6g\n", discs, r, sum / discs);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string cmd = argc > 1 ? argv[1] : "";
    try {
        if (cmd == "diff" && argc == 4) return Diff(argv[2], argv[3]);
        if (cmd == "exr-equal" && argc == 4) return ExrEqual(argv[2], argv[3]);
        if (cmd == "exr-channels" && argc == 3) return ExrChannels(argv[2]);
        if (cmd == "exr-relmse" && (argc == 4 || (argc >= 7 && argc % 2 == 1))) return ExrRelMse(argc, argv);
        if (cmd == "colour" && argc == 8)
            return ColourCentroid(argv[2], argv[3], std::atoi(argv[4]), std::atoi(argv[5]), std::atoi(argv[6]),
                                  std::atoi(argv[7]));
        if ((cmd == "stats" || cmd == "centroid") && argc == 7) {
            const int x0 = std::atoi(argv[3]), y0 = std::atoi(argv[4]), x1 = std::atoi(argv[5]),
                      y1 = std::atoi(argv[6]);
            return cmd == "stats" ? Stats(argv[2], x0, y0, x1, y1) : Centroid(argv[2], x0, y0, x1, y1);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "image_probe: %s\n", e.what());
        return 2;
    }
    std::fprintf(stderr, "usage: image_probe diff|stats|centroid|colour|exr-equal|exr-channels|exr-relmse ...\n");
    return 2;
}
