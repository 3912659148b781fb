#include "denoise/rae_weights.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>

#include "core/data_dir.h"
#include "core/error.h"
#include "denoise/denoiser.h"
#include "denoise/planes.h"

namespace fovrt {
namespace {

constexpr char kMagic[4] = {'R', 'A', 'E', 'W'};
constexpr uint32_t kVersion = 1;

class Reader {
public:
    Reader(const std::vector<uint8_t>& bytes, const std::string& what) : bytes_(bytes), what_(what) {}
    template <class T>
    T Get(const char* field) {
        if (pos_ + sizeof(T) > bytes_.size()) Fail("{}: truncated at {} (byte {})", what_, field, pos_);
        T v;
        std::memcpy(&v, bytes_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return v;
    }
    void Floats(std::vector<float>& out, size_t n, const char* field) {
        if (pos_ + 4 * n > bytes_.size()) Fail("{}: truncated in {} (byte {})", what_, field, pos_);
        out.resize(n);
        std::memcpy(out.data(), bytes_.data() + pos_, 4 * n);
        pos_ += 4 * n;
    }
    size_t Pos() const { return pos_; }

private:
    const std::vector<uint8_t>& bytes_;
    std::string what_;
    size_t pos_ = 0;
};

// The (out, in) of every conv the widths imply, in file order.
std::vector<std::pair<int, int>> ExpectedShapes(int inChannels, const std::vector<int>& widths) {
    std::vector<std::pair<int, int>> s;
    int c = inChannels;
    for (int w : widths) {
        s.insert(s.end(), {{w, c}, {w, w}, {w, 2 * w}, {w, w}});
        c = w;
    }
    s.insert(s.end(), {{c, c}, {c, c}, {c, 2 * c}, {c, c}});
    for (int l = int(widths.size()) - 1; l >= 0; --l) {
        s.insert(s.end(), {{widths[l], c + widths[l]}, {widths[l], widths[l]}});
        c = widths[l];
    }
    s.push_back({3, c});
    return s;
}

// The resolution scale (1/4^level) of each conv, in file order.
std::vector<double> ConvScales(int levels) {
    std::vector<double> s;
    for (int l = 0; l < levels; ++l) s.insert(s.end(), 4, 1.0 / double(1 << (2 * l)));
    s.insert(s.end(), 4, 1.0 / double(1 << (2 * levels)));
    for (int l = levels - 1; l >= 0; --l) s.insert(s.end(), 2, 1.0 / double(1 << (2 * l)));
    s.push_back(1.0);
    return s;
}

}  // namespace

size_t RaeWeights::Parameters() const {
    size_t n = 0;
    for (const RaeConv& c : convs) n += c.weight.size() + c.bias.size();
    return n;
}

double RaeWeights::FlopsPerPixel() const {
    const std::vector<double> scales = ConvScales(Levels());
    double f = 0.0;
    for (size_t i = 0; i < convs.size(); ++i) f += 2.0 * 9.0 * convs[i].in * convs[i].out * scales[i];
    return f;
}

RaeWeights ParseRaeWeights(const std::vector<uint8_t>& bytes, const std::string& what) {
    Reader r(bytes, what);
    char magic[4];
    for (char& m : magic) m = r.Get<char>("magic");
    if (std::memcmp(magic, kMagic, 4) != 0) Fail("{}: not a .raew weight file (magic)", what);
    RaeWeights w;
    w.version = r.Get<uint32_t>("version");
    if (w.version != kVersion) Fail("{}: .raew version {} (this build reads {})", what, w.version, kVersion);
    const uint32_t levels = r.Get<uint32_t>("levels");
    w.inChannels = int(r.Get<uint32_t>("in_channels"));
    const uint32_t flags = r.Get<uint32_t>("flags");
    w.sampleCount = (flags & kRaeFlagSampleCount) != 0;
    w.gamma = r.Get<float>("gamma");
    if (levels < 1 || levels > 8) Fail("{}: {} levels (1..8 supported)", what, levels);
    if (w.inChannels != (w.sampleCount ? 8 : 7))
        Fail("{}: {} input channels with sample-count flag {} (7 or 8 with the flag)", what, w.inChannels,
             w.sampleCount);
    if (!(w.gamma > 0.0f)) Fail("{}: gamma {} must be > 0", what, w.gamma);
    for (uint32_t l = 0; l < levels; ++l) {
        w.widths.push_back(int(r.Get<uint32_t>("widths")));
        if (w.widths.back() < 1 || w.widths.back() > 1024) Fail("{}: width {} out of range", what, w.widths.back());
    }
    const auto shapes = ExpectedShapes(w.inChannels, w.widths);
    const uint32_t count = r.Get<uint32_t>("conv_count");
    if (count != shapes.size()) Fail("{}: {} convs, the widths imply {}", what, count, shapes.size());
    for (size_t i = 0; i < shapes.size(); ++i) {
        RaeConv c;
        c.out = int(r.Get<uint32_t>("conv out"));
        c.in = int(r.Get<uint32_t>("conv in"));
        if (c.out != shapes[i].first || c.in != shapes[i].second)
            Fail("{}: conv {} is {}→{}, the widths imply {}→{}", what, i, c.in, c.out, shapes[i].second,
                 shapes[i].first);
        r.Floats(c.weight, size_t(c.out) * c.in * 9, "weights");
        r.Floats(c.bias, size_t(c.out), "bias");
        w.convs.push_back(std::move(c));
    }
    if (r.Pos() != bytes.size()) Fail("{}: {} trailing bytes", what, bytes.size() - r.Pos());
    return w;
}

RaeWeights LoadRaeWeights(const std::filesystem::path& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) Fail("{}: cannot open RAE weights (denoise.rae.weights)", path.string());
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    return ParseRaeWeights(bytes, path.string());
}

void SaveRaeWeights(const std::filesystem::path& path, const RaeWeights& w) {
    std::ofstream f(path, std::ios::binary);
    if (!f) Fail("{}: cannot write", path.string());
    auto put = [&](auto v) { f.write(reinterpret_cast<const char*>(&v), sizeof(v)); };
    f.write(kMagic, 4);
    put(uint32_t(kVersion));
    put(uint32_t(w.widths.size()));
    put(uint32_t(w.inChannels));
    put(uint32_t(w.sampleCount ? kRaeFlagSampleCount : 0));
    put(float(w.gamma));
    for (int width : w.widths) put(uint32_t(width));
    put(uint32_t(w.convs.size()));
    for (const RaeConv& c : w.convs) {
        put(uint32_t(c.out));
        put(uint32_t(c.in));
        f.write(reinterpret_cast<const char*>(c.weight.data()), std::streamsize(c.weight.size() * 4));
        f.write(reinterpret_cast<const char*>(c.bias.data()), std::streamsize(c.bias.size() * 4));
    }
    if (!f) Fail("{}: write failed", path.string());
}

size_t RaeHiddenStateBytes(const RaeWeights& weights, int paddedWidth, int paddedHeight) {
    size_t n = 0;
    const int L = weights.Levels();
    for (int l = 0; l <= L; ++l) {
        const int c = weights.widths[size_t(std::min(l, L - 1))];
        n += size_t(c) * size_t(paddedWidth >> l) * size_t(paddedHeight >> l) * sizeof(float);
    }
    return n;
}

std::filesystem::path ResolveRaeWeightsPath(const DenoiserParams& params) {
    const std::filesystem::path p(params.rae.weights);
    if (p.is_absolute() || std::filesystem::exists(p)) return p;
    const std::filesystem::path shipped = DataRoot() / p;
    return std::filesystem::exists(shipped) ? shipped : p;
}

std::shared_ptr<const RaeWeights> SharedRaeWeights(const DenoiserParams& params) {
    static std::mutex mutex;
    static std::map<std::string, std::shared_ptr<const RaeWeights>> loaded;
    const std::string path = ResolveRaeWeightsPath(params).string();
    std::lock_guard<std::mutex> lock(mutex);
    auto it = loaded.find(path);
    if (it != loaded.end()) return it->second;
    auto w = std::make_shared<const RaeWeights>(LoadRaeWeights(path));
    loaded.emplace(path, w);
    return w;
}

std::vector<RaeTensorSlot> RaeTensorLayout(const RaeWeights& w, int pw, int ph) {
    std::vector<RaeTensorSlot> slots;
    size_t offset = 0;
    auto add = [&](std::string name, int channels, int level, bool history = false) {
        RaeTensorSlot s{std::move(name), channels, pw >> level, ph >> level, offset, history};
        offset += s.Floats();
        slots.push_back(std::move(s));
    };
    const int L = w.Levels();
    add("rae.input", w.inChannels, 0);
    for (int l = 0; l <= L; ++l) {
        const int c = w.widths[size_t(std::min(l, L - 1))];
        const std::string p = l < L ? "rae.enc" + std::to_string(l) : "rae.bottleneck";
        add(p + ".x", c, l);
        add(p + ".a", c, l);
        add(p + ".t", c, l);
        add("rae.hidden" + std::to_string(l) + ".A", c, l, true);
        add("rae.hidden" + std::to_string(l) + ".B", c, l, true);
        if (l < L) add(p + ".pool", c, l + 1);
    }
    for (int l = L - 1; l >= 0; --l) {
        add("rae.dec" + std::to_string(l) + ".a", w.widths[size_t(l)], l);
        add("rae.dec" + std::to_string(l) + ".b", w.widths[size_t(l)], l);
    }
    add("rae.output", 3, 0);
    return slots;
}

const RaeTensorSlot& FindRaeSlot(const std::vector<RaeTensorSlot>& layout, const std::string& name) {
    for (const RaeTensorSlot& s : layout)
        if (s.name == name) return s;
    Fail("rae: no tensor '{}' in the layout", name);
}

std::vector<BufferPlan> PlanRaeMemory(int width, int height, const DenoiserParams& params) {
    const RaeWeights& w = *SharedRaeWeights(params);
    const int L = w.Levels();
    const int pw = RaePaddedSize(width, L), ph = RaePaddedSize(height, L);
    const size_t element = params.precision == Precision::Fp16 ? 2 : 4;
    std::vector<BufferPlan> plan;
    for (const RaeTensorSlot& s : RaeTensorLayout(w, pw, ph)) plan.push_back({s.name, s.Floats() * element, s.history});
    plan.push_back({"rae.weights", w.Parameters() * 4, false});
    plan.push_back({"staging", RaeStagingBytes(w, pw, ph, params), false});
    return plan;
}

size_t RaeStagingBytes(const RaeWeights& weights, int paddedWidth, int paddedHeight, const DenoiserParams& params) {
    const size_t element = params.precision == Precision::Fp16 ? 2 : 4;
    const size_t pixels = size_t(paddedWidth) * size_t(paddedHeight);
    const size_t transfers = StagingAlign(pixels * size_t(weights.inChannels) * element) + StagingAlign(pixels * 3 * element);
    return std::min(transfers, params.transferRingBytes);
}

}  // namespace fovrt
