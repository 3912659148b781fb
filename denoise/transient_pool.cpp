#include "denoise/transient_pool.h"

#include <fmt/format.h>

#include <algorithm>
#include <climits>

#include "core/check.h"

namespace fovrt {

namespace {

// How a command touches a plane, for lifetimes.
enum class Touch : uint8_t {
    Defines,  // writes every element a later use reads (the whole plane, or appends to a list
              // whose readers take only this frame's count)
    Uses,     // reads it, or writes part of it
};

bool Always(When pass, When command) { return pass == When::Always && command == When::Always; }

// A dispatch's write defines its plane when it covers every pixel of the grid, or appends to a
// list (the reprojection's fallback pixels, the classify pass's listed pixels) that is read only
// through the count this frame wrote. A dispatch over a pixel list writes part of a plane.
bool DispatchDefines(const DispatchCommand& d, const Binding& b) {
    if (b.access != Access::Write || d.grid == Grid::PixelList) return false;
    return b.coverage == Coverage::EveryPixel || b.coverage == Coverage::ListedPixels ||
           b.coverage == Coverage::FallbackPixels;
}

// Every plane buffer a command touches (a history by the side it names; both parities give the
// same lifetimes, so parity 0 stands for both).
template <typename F>
void ForEachTouch(const Command& command, F&& f) {
    auto key = [](const PlaneRef& ref) { return ResolveSide(ref, 0); };
    std::visit(
        [&](const auto& op) {
            using T = std::decay_t<decltype(op)>;
            if constexpr (std::is_same_v<T, DispatchCommand>) {
                for (const Binding& b : op.bindings)
                    if (b.access != Access::Unused) f(key(b.plane), DispatchDefines(op, b) ? Touch::Defines : Touch::Uses);
                if (op.grid == Grid::PixelList) f(BufferKey{op.listArgs, BufferSide::None}, Touch::Uses);
            } else if constexpr (std::is_same_v<T, FillCommand>) {
                f(key(op.plane), Touch::Defines);
            } else if constexpr (std::is_same_v<T, CopyCommand>) {
                f(key(op.from), Touch::Uses);
                f(key(op.to), Touch::Defines);
            } else if constexpr (std::is_same_v<T, UploadCommand>) {
                f(key(op.to), op.coverage == Coverage::EveryPixel ? Touch::Defines : Touch::Uses);
            } else if constexpr (std::is_same_v<T, DownloadCommand>) {
                f(key(op.from), Touch::Uses);
            }
            // ClearCommand (a reset: no transient value survives it anyway), BarrierCommand.
        },
        command.op);
}

bool MayBeTransient(PlaneKind kind) { return !IsHistory(kind) && !IsStaging(kind) && !IsFixedSize(kind); }

}  // namespace

std::map<BufferKey, PlaneLifetime> PlaneLifetimes(const DenoiserPlan& plan) {
    struct Seen {
        int first = -1, last = -1;
        bool definedFirst = true;  // every touch in the first epoch an always-run Defines
    };
    std::map<BufferKey, Seen> seen;
    int epoch = 0;
    for (const PlannedPass& pass : plan.passes)
        for (const Command& command : pass.commands) {
            // A barrier some frames skip separates nothing: those frames run both sides at once.
            if (std::holds_alternative<BarrierCommand>(command.op)) {
                if (Always(pass.when, command.when)) ++epoch;
                continue;
            }
            const bool always = Always(pass.when, command.when);
            ForEachTouch(command, [&](const BufferKey& key, Touch touch) {
                Seen& s = seen[key];
                if (s.first < 0) s.first = epoch;
                if (s.first == epoch && !(always && touch == Touch::Defines)) s.definedFirst = false;
                s.last = epoch;
            });
        }
    std::map<BufferKey, PlaneLifetime> lifetimes;
    for (const PlanePlacement& p : plan.planes) {
        auto it = seen.find(p.key);
        if (it == seen.end()) {  // named only by a command no barrier count reaches (none today)
            lifetimes[p.key] = {false, 0, INT_MAX};
            continue;
        }
        const Seen& s = it->second;
        lifetimes[p.key] = {MayBeTransient(p.key.id.kind) && s.definedFirst, s.first,
                            p.readAfterFrame ? INT_MAX : s.last};
    }
    return lifetimes;
}

void PlaceInTransientPool(DenoiserPlan& plan) {
    const std::map<BufferKey, PlaneLifetime> lifetimes = PlaneLifetimes(plan);
    plan.buffers.clear();
    std::vector<size_t> transient;  // indices into plan.planes
    for (size_t i = 0; i < plan.planes.size(); ++i) {
        PlanePlacement& p = plan.planes[i];
        if (lifetimes.at(p.key).transient) {
            transient.push_back(i);
            continue;
        }
        p.allocation = plan.buffers.size();
        // The staging ring holds only what one frame streams: frames of other denoisers may share it.
        plan.buffers.push_back({BufferName(p.key), p.bytes, IsHistory(p.key.id.kind), false, IsStaging(p.key.id.kind)});
    }
    // Interval placement in order of first write (larger planes first within an epoch): a slot is
    // free when every plane in it died before this one is first written.
    std::stable_sort(transient.begin(), transient.end(), [&](size_t a, size_t b) {
        const PlaneLifetime &la = lifetimes.at(plan.planes[a].key), &lb = lifetimes.at(plan.planes[b].key);
        if (la.first != lb.first) return la.first < lb.first;
        return plan.planes[a].bytes > plan.planes[b].bytes;
    });
    struct Slot {
        size_t bytes = 0;
        int freeFrom = 0;  // the first epoch after its planes' last use
    };
    std::vector<Slot> slots;
    for (size_t i : transient) {
        PlanePlacement& p = plan.planes[i];
        const PlaneLifetime& life = lifetimes.at(p.key);
        size_t best = slots.size();
        auto cost = [&](const Slot& s) {  // (bytes it grows by, bytes it leaves unused)
            return s.bytes >= p.bytes ? std::pair(size_t(0), s.bytes - p.bytes) : std::pair(p.bytes - s.bytes, size_t(0));
        };
        for (size_t s = 0; s < slots.size(); ++s)
            if (slots[s].freeFrom <= life.first && (best == slots.size() || cost(slots[s]) < cost(slots[best])))
                best = s;
        if (best == slots.size()) slots.push_back({});
        slots[best].bytes = std::max(slots[best].bytes, p.bytes);
        slots[best].freeFrom = life.last == INT_MAX ? INT_MAX : life.last + 1;
        p.allocation = plan.buffers.size() + best;
    }
    for (size_t s = 0; s < slots.size(); ++s)
        plan.buffers.push_back({fmt::format("transient.{}", s), slots[s].bytes, false, true, true});
}

bool HeldAfterFrame(const DenoiserPlan& plan, const BufferKey& key) {
    const std::map<BufferKey, PlaneLifetime> lifetimes = PlaneLifetimes(plan);
    const PlanePlacement* self = nullptr;
    for (const PlanePlacement& p : plan.planes)
        if (p.key == key) self = &p;
    FOVRT_CHECK(self != nullptr);
    for (const PlanePlacement& p : plan.planes)
        if (p.allocation == self->allocation && lifetimes.at(p.key).first > lifetimes.at(key).first) return false;
    return true;
}

size_t PeakLiveTransientBytes(const DenoiserPlan& plan) {
    const std::map<BufferKey, PlaneLifetime> lifetimes = PlaneLifetimes(plan);
    std::map<int, size_t> live;  // epoch → bytes (only epochs where a lifetime starts can peak)
    for (const PlanePlacement& p : plan.planes) {
        const PlaneLifetime& life = lifetimes.at(p.key);
        if (life.transient) live[life.first] = 0;
    }
    for (auto& [epoch, bytes] : live)
        for (const PlanePlacement& p : plan.planes) {
            const PlaneLifetime& life = lifetimes.at(p.key);
            if (life.transient && life.first <= epoch && epoch <= life.last) bytes += p.bytes;
        }
    size_t peak = 0;
    for (const auto& [epoch, bytes] : live) peak = std::max(peak, bytes);
    return peak;
}

std::string AliasingConflict(const DenoiserPlan& plan) {
    const std::map<BufferKey, PlaneLifetime> lifetimes = PlaneLifetimes(plan);
    for (size_t a = 0; a < plan.planes.size(); ++a)
        for (size_t b = a + 1; b < plan.planes.size(); ++b) {
            const PlanePlacement &pa = plan.planes[a], &pb = plan.planes[b];
            if (pa.allocation != pb.allocation) continue;
            const PlaneLifetime &la = lifetimes.at(pa.key), &lb = lifetimes.at(pb.key);
            const std::string where = plan.buffers.at(pa.allocation).name;
            if (!la.transient || !lb.transient)
                return fmt::format("{} and {} share {}, but {} holds a value across frames", BufferName(pa.key),
                                   BufferName(pb.key), where, BufferName((la.transient ? pb : pa).key));
            if (la.Overlaps(lb))
                return fmt::format("{} (epochs {}..{}) and {} (epochs {}..{}) share {} while both are live",
                                   BufferName(pa.key), la.first, la.last, BufferName(pb.key), lb.first, lb.last,
                                   where);
        }
    for (const PlanePlacement& p : plan.planes)
        if (p.allocation >= plan.buffers.size() || plan.buffers[p.allocation].bytes < p.bytes)
            return fmt::format("{} does not fit its allocation", BufferName(p.key));
    return "";
}

}  // namespace fovrt
